#pragma once
// outer: the method of successive approximations (theory.md §5), for any fixed-point map
// x = Psi(x) on a state made of named blocks. Today the state is the nodal slips phi of the
// contact surface (driver/tresca_map.hpp); the Coulomb model iterates on (phi, lambda_n) with the
// same loop, stopping rule, stall detection and Anderson mixing.
//
//   x^0 given; for k = 1, 2, ...: g = Psi(x^(k-1)); err(k) = max over blocks of
//   ||g_b - x_b^(k-1)|| / max(||g_b||, scale_b); x^k = g (or Anderson's mix); stop when
//   err(k) <= tol.

#include <array>
#include <atomic>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fricon/core/enum_names.hpp"
#include "fricon/core/range.hpp"
#include "fricon/core/types.hpp"
#include "fricon/outer/acceleration.hpp"

namespace fricon::outer {

/// Why the outer loop stopped (and, set by the caller after it, whether the final iterate passed
/// its certificate).
enum class OuterTermination {
  Converged,          ///< err(k) <= tol
  IterationLimit,     ///< max_iterations reached first
  Stalled,            ///< no new smallest err(k) for stall_window iterations: not contracting
  QpFailed,           ///< the inner solve of an iteration failed
  Interrupted,        ///< a stop was requested (Ctrl-C, SIGTERM)
  CertificateFailed,  ///< converged, but the optimality residuals of the result are too large
};

/// The ranges of OuterOptions' fields; the problem file's [solver] keys use the same.
inline constexpr Range kOuterTolRange = positive();
inline constexpr Range kOuterMaxRange = integer_at_least(1);
inline constexpr Range kAndersonDepthRange = integer_in(1, 20);

struct OuterOptions {
  Real tol = 1.0e-4;        ///< stop when err(k) <= tol; kOuterTolRange
  int max_iterations = 50;  ///< kOuterMaxRange
  Acceleration acceleration = Acceleration::None;
  int anderson_depth = 1;  ///< previous iterates Anderson mixing uses; kAndersonDepthRange
  /// Iterations without a new smallest err(k) after which the loop is stalled; >= 1.
  int stall_window = 4;

  /// Throws InputError naming the first field out of range, its value and the range.
  void validate() const;
};

/// A named block of the state, e.g. {"phi", n_surface_nodes} (nodal slips [m]).
struct StateBlock {
  std::string name;
  Index size = 0;
  /// A floor [the block's unit] of the norm its change is relative to: err(k) of the block is
  /// ||image - x|| / max(||image||, scale). 0: relative to the image alone. A block whose
  /// answer may be zero (the pressures of a step unloaded to nothing) needs a scale that does
  /// not vanish with it (theory.md §5.2).
  Real scale = 0.0;
};

/// How one application of the map went.
enum class StepStatus {
  Ok,
  Failed,       ///< the inner solve failed (the message says why)
  Interrupted,  ///< the inner solve was stopped on request
};

struct MapStep {
  StepStatus status = StepStatus::Ok;
  std::string message;  ///< why, when not Ok
};

/// The map x -> Psi(x).
class FixedPointMap {
 public:
  virtual ~FixedPointMap() = default;
  /// The blocks of the state in order; their sizes add up to the size of the state.
  virtual std::vector<StateBlock> layout() const = 0;
  /// image := Psi(x) at outer iteration k (1-based). A step that fails still fills `image` with
  /// what it reached, so that the last iterate can be reported.
  virtual MapStep apply(int k, const VectorXd& x, VectorXd& image) = 0;
  /// For a loop that does not contract: what may cause it, as a clause ("the friction law's
  /// Lipschitz constant 3 1/m may be too large"); empty if nothing is known.
  virtual std::string stall_hint() const { return {}; }
};

/// One iteration as the monitor sees it.
struct OuterIteration {
  int k = 0;
  Real err = 0.0;               ///< err(k), the largest of block_err
  std::vector<Real> block_err;  ///< relative change of each block (layout order)
  double seconds = 0.0;         ///< wall time of this iteration [s]
};

struct OuterReport {
  OuterTermination termination = OuterTermination::IterationLimit;
  std::string message;  ///< one sentence: why the loop stopped (empty when converged)
  int iterations = 0;
  std::vector<Real> err_history;                 ///< err(k), k = 1, 2, ...
  std::vector<std::vector<Real>> block_history;  ///< per iteration, the change of each block
  /// Observed contraction factor: geometric mean of err(k)/err(k-1) over the last (up to three)
  /// iterations after the first; 0 if fewer than three iterations.
  Real contraction_ratio = 0.0;
  /// The last err(k): ||Psi(x) - x|| / ||Psi(x)|| at the returned state.
  Real fixed_point_residual = 0.0;

  bool converged() const { return termination == OuterTermination::Converged; }
};

/// Runs the successive approximations from x (the initial state, sized as map.layout()); on
/// return x is the state the last application of Psi started from. `monitor` is called after
/// every iteration; a true `*stop` ends the loop after the current iteration (Interrupted).
/// Throws InputError for invalid options or a state of the wrong size.
OuterReport iterate(FixedPointMap& map, VectorXd& x, const OuterOptions& options,
                    const std::function<void(const OuterIteration&)>& monitor = {},
                    const std::atomic<bool>* stop = nullptr);

/// ||now - before|| / max(||now||, scale) (scale >= 0, StateBlock::scale); with a zero
/// denominator 0 when both are zero, 1 when `before` is not (a relative change of everything,
/// not convergence).
Real relative_change(const VectorXd& now, const VectorXd& before, Real scale = 0.0);

/// The contraction ratio of OuterReport for a history of err(k).
Real contraction_ratio(const std::vector<Real>& err);

/// Whether the last `window` values of err(k) are all at or above the smallest before them.
bool stalled(const std::vector<Real>& err, size_t window);

}  // namespace fricon::outer

FRICON_ENUM_NAMES(fricon::outer::OuterTermination, "outer termination",
                  {outer::OuterTermination::Converged, "converged"},
                  {outer::OuterTermination::IterationLimit, "iteration_limit"},
                  {outer::OuterTermination::Stalled, "stalled"},
                  {outer::OuterTermination::QpFailed, "qp_failed"},
                  {outer::OuterTermination::Interrupted, "interrupted"},
                  {outer::OuterTermination::CertificateFailed, "certificate_failed"});
