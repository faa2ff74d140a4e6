#include "fricon/qp/mpgp.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/core/range.hpp"
#include "fricon/core/timer.hpp"
#include "fricon/qp/mpgp_kernels.hpp"

namespace fricon::qp {

// ---------------------------------------------------------------------------------------------
// Options and report

void MpgpOptions::validate() const {
  require("MpgpOptions::rel_tolerance", rel_tolerance, non_negative());
  require("MpgpOptions::abs_tolerance", abs_tolerance, non_negative());
  require("MpgpOptions::max_iterations", max_iterations, integer_at_least(0));
  require("MpgpOptions::gamma", gamma, positive());
  require("MpgpOptions::step_factor", step_factor, Range{false, 0.0, 2.0, true, false, {}});
  require("MpgpOptions::norm_A (0 = estimate by power iteration)", norm_A, non_negative());
  require("MpgpOptions::power_iterations", power_iterations, integer_at_least(1));
  require("MpgpOptions::power_tolerance", power_tolerance, positive());
  require("MpgpOptions::active_tolerance", active_tolerance,
          Range{false, 0.0, 1e-3, false, false, {}});
  if (!enum_is_valid(variant) || !enum_is_valid(expansion) || !enum_is_valid(active_discs))
    throw InputError(fmt::format(
        "MpgpOptions: variant {}, expansion {} or active_discs {} is not an enumerator",
        static_cast<int>(variant), static_cast<int>(expansion), static_cast<int>(active_discs)));
  require("MpgpOptions::expansion_length_factor", expansion_length_factor,
          Range{false, 0.0, 2.0, true, false, {}});
}

std::string MpgpReport::brief() const {
  // Paper with the Fixed expansion prints as before the expansion choice existed.
  const std::string exp =
      (expansion == MpgpExpansion::Fixed ? std::string()
                                         : fmt::format(", exp {}", enum_name(expansion))) +
      (active_discs == MpgpDiscFace::Held ? "" : ", discs turned");
  const std::string exp_fallbacks = expansion == MpgpExpansion::Fixed
                                        ? std::string()
                                        : fmt::format("; {} exp fallback", n_expansion_fallbacks);
  if (variant == MpgpVariant::Paper) {
    const std::string name = exp.empty() ? "MPGP" : fmt::format("MPGP[paper{}]", exp);
    return fmt::format(
        "{} {}: {} it ({} cg, {} exp, {} prop{}), {} products (+{} power), |gP|/|r| = {:.3e}", name,
        enum_name(termination), iterations, n_cg, n_expansion, n_proportioning, exp_fallbacks,
        n_products, n_power_products, rel_gp);
  }
  return fmt::format(
      "MPGP[{}{}] {}: {} it ({} cg, {} exp, {} prop; {} fallback, {} refresh{}), {} products (+{} "
      "power), |gP|/|r| = {:.3e}",
      enum_name(variant), exp, enum_name(termination), iterations, n_cg, n_expansion,
      n_proportioning, n_fallbacks, n_refreshes, exp_fallbacks, n_products, n_power_products,
      rel_gp);
}

std::string MpgpReport::full() const {
  std::string s;
  auto line = [&s](std::string_view key, const std::string& value) {
    s += fmt::format("  {:<22} {}\n", key, value);
  };
  s += "MPGP report\n";
  line("termination", std::string(enum_name(termination)));
  line("message", message);
  line("variant", std::string(enum_name(variant)));
  line("expansion", std::string(enum_name(expansion)));
  line("active_discs", std::string(enum_name(active_discs)));
  line("iterations", std::to_string(iterations));
  line("n_cg", std::to_string(n_cg));
  line("n_expansion", std::to_string(n_expansion));
  line("n_proportioning", std::to_string(n_proportioning));
  line("n_fallbacks", std::to_string(n_fallbacks));
  line("n_refreshes", std::to_string(n_refreshes));
  line("n_expansion_products", std::to_string(n_expansion_products));
  line("n_expansion_fallbacks", std::to_string(n_expansion_fallbacks));
  line("n_products", std::to_string(n_products));
  line("n_power_products", std::to_string(n_power_products));
  line("n_preconditioner", std::to_string(n_preconditioner));
  line("norm_A_used",
       fmt::format("{:.6e} ({})", norm_A_used, norm_A_estimated ? "power iteration" : "given"));
  line("alpha_bar_used", fmt::format("{:.6e}", alpha_bar_used));
  line("norm_b", fmt::format("{:.6e}", norm_b));
  line("reference_norm", fmt::format("{:.6e}", reference_norm));
  line("norm_gp", fmt::format("{:.6e}", norm_gp));
  line("rel_gp", fmt::format("{:.6e}", rel_gp));
  line("objective", fmt::format("{:.15e}", objective));
  line("n_objective_increases", std::to_string(n_objective_increases));
  line("seconds", fmt::format("{:.6f}", seconds));
  return s;
}

Eigen::VectorXd resisted_part(const Eigen::VectorXd& b, const SeparableConstraints& c) {
  FRICON_CHECK(b.size() == c.size(), "b has " << b.size() << " entries for " << c.size());
  Eigen::VectorXd r(b.size());
  for (std::size_t k = 0; k < c.blocks.size(); ++k) {
    const Index o = c.blocks[k].offset;
    if (c.blocks[k].kind == BlockKind::Free) {
      r(o) = b(o);  // unconstrained: x_i = 0 is optimal only for b_i = 0, so all of b_i counts
    } else if (c.blocks[k].kind == BlockKind::Bound) {
      r(o) = std::max(b(o), 0.0);
    } else {
      const bool pinned = c.radius(static_cast<Index>(k)) == 0.0;
      r(o) = pinned ? 0.0 : b(o);
      r(o + 1) = pinned ? 0.0 : b(o + 1);
    }
  }
  return r;
}

// ---------------------------------------------------------------------------------------------
// Power method

double estimate_norm(const Operator& A, Index n, int max_iterations, double tolerance,
                     long* n_products, const DualSpace& space) {
  FRICON_CHECK(n >= 0, "n = " << n);
  if (space.size(n) == 0 || max_iterations <= 0) return 0.0;
  Eigen::VectorXd v(n);
  Eigen::VectorXd w(n);
  // Deterministic, non-symmetric start vector with entries in [0.5, 1.5) (a 64-bit mix of i), so
  // that it is unlikely to be orthogonal to the dominant eigenvector of a structured A.
  for (Index i = 0; i < n; ++i) {
    std::uint64_t z = static_cast<std::uint64_t>(i + 1) * 0x9E3779B97F4A7C15ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    v(i) = 0.5 + static_cast<double>(z >> 11) * 0x1.0p-53;
  }
  v /= space.norm(v);
  double est = 0.0;
  for (int k = 1; k <= max_iterations; ++k) {
    A(v, w);
    if (n_products) ++*n_products;
    FRICON_CHECK(w.size() == n,
                 "operator returned a vector of size " << w.size() << ", expected " << n);
    const double nw = space.norm(w);
    if (!std::isfinite(nw)) {
      throw NumericalError(
          fmt::format("power iteration: ||A v|| = {} at step {} (n = {})", nw, k, n));
    }
    if (nw == 0.0) return 0.0;
    const double prev = est;
    est = nw;  // ||A v|| with ||v|| = 1: a lower bound of ||A||, nondecreasing for SPD A
    v = w / nw;
    if (k > 1 && std::abs(est - prev) <= tolerance * est) break;
  }
  return est;
}

// ---------------------------------------------------------------------------------------------
// MPGP (docs/theory.md §4.2, [HL09]; "line n" is a line of the MPGP algorithm as listed there)

namespace {

using detail::Kernels;
using detail::SpectralLength;
using detail::Split;

/// Safety factor on the rounding level eps sum_i ||g_i|| ||x_i|| below which g^T d is trusted
/// (see Mpgp::spectral_move). Measured: 1 to 64 give about the same counts.
constexpr double kRoundingFactor = 4.0;

/// What changes from one iteration to the next. (The step counters are those of MpgpReport.)
struct MpgpState {
  /// Work vectors of the size of x, allocated once.
  MpgpState(Eigen::VectorXd& iterate, const SpectralLength& trial_length)
      : x(iterate),
        g(x.size()),
        p(x.size()),
        Ap(x.size()),
        phi(x.size()),
        beta(x.size()),
        spectral(trial_length) {}

  /// The work vectors of the Optimal and ProjectedCG expansions (allocated at their first use).
  void allocate_expansion_work() {
    if (x_saved.size() == x.size()) return;
    x_saved.resize(x.size());
    g_saved.resize(x.size());
    gr.resize(x.size());
  }

  Eigen::VectorXd& x;       ///< the iterate (the caller's vector), feasible
  Eigen::VectorXd g;        ///< the gradient A x - b, recomputed or updated recursively
  Eigen::VectorXd p;        ///< the CG direction; also the direction d of a spectral move
  Eigen::VectorXd Ap;       ///< A p
  Eigen::VectorXd phi;      ///< the free gradient at x (docs/theory.md §4.1)
  Eigen::VectorXd beta;     ///< the chopped gradient at x
  Eigen::VectorXd z;        ///< the preconditioned free gradient (sized by the first use)
  Eigen::VectorXd Dp;       ///< the turned discs' curvature times p (MpgpDiscFace::Turned)
  Eigen::VectorXd x_saved;  ///< x (and g_saved its g) before an expansion move that may fall back
  Eigen::VectorXd g_saved;
  bool g_saved_exact = true;  ///< g_exact of g_saved
  Eigen::VectorXd gr;         ///< the reduced free gradient (direction of the Optimal expansion)
  Split split;                ///< ||g^P||^2, ||phi||^2, ||beta||^2 and phitilde^T phi at x
  /// True while g has been updated recursively (g -= a A p) since the last product A x and the
  /// stopping test must be certified with a recomputed g (BarzilaiBorwein; Paper accepts the
  /// recursive gradient, as [HL09] does).
  bool recursive = false;
  /// What p still has to become before the next CG or expansion step (Mpgp::next_direction):
  /// the direction is formed only when a step takes it, so that a preconditioner is not applied
  /// for a proportioning step, which moves along g instead.
  enum class Direction { Ready, Restart, Conjugate } direction = Direction::Ready;
  double pAp = 0.0;     ///< p^T (A + D) p of the last CG step (for Direction::Conjugate; §4.7)
  bool turned = false;  ///< the last CG step turned discs (its p^T A p includes D p; §4.7)
  /// g = A x - b up to rounding: false from a turned discs' radial return (which g does not
  /// follow, §4.7) until the next recomputation of g. q(x) = x^T (g - b) / 2 is then inexact.
  bool g_exact = true;
  bool q_prev_exact = true;  ///< g_exact when q_prev was recorded
  double q_prev = 0.0;       ///< q after the last step (for n_objective_increases)
  bool stopped = false;      ///< the monitor returned false
  SpectralLength spectral;   ///< the trial length of the spectral moves (BarzilaiBorwein)
};

/// How the iteration ends.
struct Stop {
  QpTermination termination;
  std::string message;
};

/// What a step did: its kind ('c', 'e', 'p'), its length (MpgpIteration::alpha) and, if it failed
/// (A found not positive definite along a direction, or non-finite values), why.
struct MpgpStep {
  char kind;
  double alpha = 0.0;
  std::optional<std::string> failure;
};

MpgpStep taken(char kind, double alpha) {
  return {kind, alpha, std::nullopt};
}

MpgpStep failed(char kind, std::string why) {
  return {kind, 0.0, std::move(why)};
}

/// One run of MPGP from a feasible x: the fixed data, the state and the steps.
class Mpgp {
 public:
  /// rep must hold norm_b > 0, norm_A_used and alpha_bar_used.
  Mpgp(const Operator& A, const Eigen::VectorXd& b, const SeparableConstraints& c,
       const MpgpOptions& opt, MpgpReport& rep, Eigen::VectorXd& x);

  /// Iterates until a Stop and completes the report (but for iterations and seconds).
  void run();

 private:
  bool proportional() const;
  MpgpStep cg_or_expansion_step();
  MpgpStep cg_step(double a_cg, double pHp, double pAp);
  MpgpStep expansion_step(double a_f, double a_cg);
  MpgpStep fixed_expansion(double a_f);
  MpgpStep optimal_expansion(double a_f);
  MpgpStep projected_cg_expansion(double a_f, double a_cg);
  void move_to_boundary(double a_f);
  MpgpStep proportioning_step();
  std::optional<double> projected_gradient_move(const Eigen::VectorXd& v);
  std::optional<double> spectral_move(const Eigen::VectorXd& v);
  double fixed_length_move(const Eigen::VectorXd& v);
  void multiply(const Eigen::VectorXd& v, Eigen::VectorXd& Av);
  void refresh_gradient();
  void split_and_restart();
  void next_direction();
  const Eigen::VectorXd& cg_direction();
  std::optional<Stop> stop_test();
  void count(char kind);
  void record(char kind, double alpha);
  void finish(const Stop& stop);

  int steps() const { return rep_.n_cg + rep_.n_expansion + rep_.n_proportioning; }
  double norm_gp() const { return std::sqrt(s_.split.gp2); }
  /// q(x) = x^T (g - b) / 2.
  double objective() const { return 0.5 * (space_.dot(s_.x, s_.g) - space_.dot(s_.x, b_)); }

  const Operator& A_;
  const Eigen::VectorXd& b_;
  const SeparableConstraints& c_;
  const MpgpOptions& opt_;
  const DualSpace& space_;  ///< where the vectors live: every reduction goes through it
  MpgpReport& rep_;
  const bool bb_;           ///< variant BarzilaiBorwein: spectral moves, certified stopping test
  const double abar_;       ///< the fixed step length alpha_bar
  const double x_scale_;    ///< the scale of x of the active-set and rounding tolerances
  const double threshold_;  ///< the stopping test: ||g^P|| <= threshold_
  const double gamma2_;     ///< Gamma^2 of the proportionality test
  Kernels kern_;            ///< remembers the discs that the last split turned
  MpgpState s_;
};

Mpgp::Mpgp(const Operator& A, const Eigen::VectorXd& b, const SeparableConstraints& c,
           const MpgpOptions& opt, MpgpReport& rep, Eigen::VectorXd& x)
    : A_(A),
      b_(b),
      c_(c),
      opt_(opt),
      space_(opt.vectors()),
      rep_(rep),
      bb_(opt.variant == MpgpVariant::BarzilaiBorwein),
      abar_(rep.alpha_bar_used),
      x_scale_(std::max(
          {space_.max_abs(x), space_.max(c.max_radius()), rep.reference_norm / rep.norm_A_used})),
      threshold_(std::max(opt.rel_tolerance * rep.reference_norm, opt.abs_tolerance)),
      gamma2_(opt.gamma * opt.gamma),
      kern_(c, opt.active_tolerance * x_scale_, opt.active_tolerance, abar_, opt.active_discs,
            space_),
      // The spectral trial lengths start from alpha_bar. Every such length lies in
      // [1/||A||, 1/lambda_min(A)]; the clamp only guards against rounding.
      s_(x, SpectralLength(abar_, 1e-3 / rep.norm_A_used, 1e12 / rep.norm_A_used)) {}

// The main loop: the stopping test, the proportionality test, then a CG or expansion step or a
// proportioning step.
void Mpgp::run() {
  // The gradient and p = phi at the projected initial guess (line 1, done by solve_mpgp).
  refresh_gradient();
  split_and_restart();
  record('s', 0.0);
  while (true) {
    if (std::optional<Stop> stop = stop_test()) return finish(*stop);  // line 3
    const long products_before = rep_.n_products;
    const MpgpStep step = proportional() ? cg_or_expansion_step()  // line 4; lines 5-12
                                         : proportioning_step();   // lines 14-15
    count(step.kind);  // a failed step is counted too: its product was spent
    if (step.kind == 'e') rep_.n_expansion_products += rep_.n_products - products_before;
    if (step.failure) return finish({QpTermination::NumericalFailure, *step.failure});
    record(step.kind, step.alpha);
  }
}

// Line 4: x is proportional iff ||beta||^2 <= Gamma^2 phitilde_{alpha_bar}^T phi (the reduced
// free gradient, as in MPRGP).
bool Mpgp::proportional() const {
  return s_.split.beta2 <= gamma2_ * s_.split.phit_phi;
}

// Lines 5-12: the CG step length a_cg along -p and the feasible one a_f decide between the CG
// step and the expansion step (1 product, A p, shared by both). Along turned discs the
// curvature is that of A + D (§4.7).
MpgpStep Mpgp::cg_or_expansion_step() {
  next_direction();
  if (kern_.turns_discs() && !(space_.dot(s_.g, s_.p) > 0.0)) {
    // The conjugate direction, taken onto the new tangents, need not descend: restart.
    s_.direction = MpgpState::Direction::Restart;
    next_direction();
  }
  multiply(s_.p, s_.Ap);
  const double pAp = space_.dot(s_.p, s_.Ap);
  const double pHp =
      kern_.turns_discs() ? pAp + kern_.turn_curvature(s_.x, s_.g, s_.p, s_.Dp) : pAp;
  const double a_cg = space_.dot(s_.g, s_.p) / pHp;
  if (!(pAp > 0.0) || !std::isfinite(pHp) || !(a_cg > 0.0) || !std::isfinite(a_cg)) {
    return failed('c', fmt::format("CG step: p^T A p = {:.3e}, step {:.3e}; A is not positive "
                                   "definite along p, or the direction is not a descent direction",
                                   pAp, a_cg));
  }
  const double a_f = kern_.max_feasible_step(s_.x, s_.p);
  return a_cg <= a_f ? cg_step(a_cg, pHp, pAp) : expansion_step(a_f, a_cg);
}

// Lines 7-8: the CG step inside the feasible set, g updated recursively; the next conjugate
// direction p = z - beta_cg p follows if the next step takes it (next_direction). The
// projection removes rounding-level infeasibility when a_cg ~ a_f, and returns turned discs to
// their circles (§4.7); their gradient is then updated to second order only, so that the
// stopping test recomputes it.
MpgpStep Mpgp::cg_step(double a_cg, double pHp, double pAp) {
  if (bb_) s_.spectral.update(space_.squared_norm(s_.p), pAp, space_.squared_norm(s_.Ap));
  s_.turned = kern_.turns_discs();
  s_.x.noalias() -= a_cg * s_.p;
  s_.g.noalias() -= a_cg * s_.Ap;
  c_.project(s_.x);
  s_.split = kern_.split(s_.x, s_.g, s_.phi, s_.beta);
  s_.pAp = pHp;
  s_.direction = MpgpState::Direction::Conjugate;
  s_.recursive = bb_ || s_.turned;
  if (s_.turned) s_.g_exact = false;
  return taken('c', a_cg);
}

// The CG direction at x, formed when a CG or expansion step takes it: phi (or its preconditioned
// image z) after a restart (line 15), z - beta_cg p after a CG step (line 8; A p and p^T A p are
// still those of that step). x, g and phi are those the direction was due at, so the iterates are
// those of forming it at once.
void Mpgp::next_direction() {
  using Direction = MpgpState::Direction;
  if (s_.direction == Direction::Restart) {
    s_.p = cg_direction();
  } else if (s_.direction == Direction::Conjugate) {
    const Eigen::VectorXd& z = cg_direction();
    const double zHp =
        s_.turned ? space_.dot(z, s_.Ap) + space_.dot(z, s_.Dp) : space_.dot(z, s_.Ap);
    s_.p = z - (zHp / s_.pAp) * s_.p;
    if (kern_.turns_discs()) kern_.restrict_to_face(s_.x, s_.p);  // tangents of the new x
  }
  s_.direction = Direction::Ready;
}

// Lines 10-12, with the move that MpgpOptions::expansion chooses; CG restarts from phi.
MpgpStep Mpgp::expansion_step(double a_f, double a_cg) {
  switch (opt_.expansion) {
    case MpgpExpansion::Optimal:
      return optimal_expansion(a_f);
    case MpgpExpansion::ProjectedCG:
      return projected_cg_expansion(a_f, a_cg);
    case MpgpExpansion::Fixed:
      break;
  }
  return fixed_expansion(a_f);
}

// Line 10: x := x - a_f p, on the boundary, g updated recursively, and the split there. Turned
// discs return to their circles (§4.7).
void Mpgp::move_to_boundary(double a_f) {
  s_.x.noalias() -= a_f * s_.p;
  s_.g.noalias() -= a_f * s_.Ap;
  if (kern_.turns_discs()) {
    c_.project(s_.x);
    s_.recursive = true;
    s_.g_exact = false;
  }
  s_.split = kern_.split(s_.x, s_.g, s_.phi, s_.beta);  // phi at the boundary point
}

// MpgpExpansion::Fixed, lines 10-12: to the boundary along -p (step a_f), then a projected move
// along the free gradient there (1 more product), without the turned discs' tangents: the move
// enlarges the active set, and along a chord of a circle it would not descend (§4.7).
MpgpStep Mpgp::fixed_expansion(double a_f) {
  move_to_boundary(a_f);
  if (kern_.turns_discs()) kern_.clear_active(s_.x, s_.phi);  // phi is formed again below
  if (!projected_gradient_move(s_.phi)) {
    return failed('e',
                  "expansion step: A is not positive definite along the projected "
                  "free-gradient direction");
  }
  split_and_restart();
  return taken('e', a_f);
}

// MpgpExpansion::Optimal (PERMON's "opt" length): from the boundary point x_b, the move along
// gr = phitilde_{alpha_bar}(x_b) of length a = factor g^T gr / gr^T A gr (1 product, A gr), the
// line-search minimiser along -gr for factor 1. x_b - t gr is feasible for t <= alpha_bar, and
// up to the largest feasible step along -gr; there q decreases (factor <= 2) and g - a A gr is
// the gradient. Beyond it the point is projected and g recomputed (1 product); should q then
// exceed q(x_b), the move is x_b - alpha_bar gr = P(x_b - alpha_bar phi), Paper's fixed-length
// move, whose gradient g_b - alpha_bar A gr is known (no product). BarzilaiBorwein's trial length
// stays as it was (updated with gr, it gave more products on the paper's brick).
MpgpStep Mpgp::optimal_expansion(double a_f) {
  move_to_boundary(a_f);
  s_.allocate_expansion_work();
  Eigen::VectorXd& gr = s_.gr;
  Eigen::VectorXd& Agr = s_.Ap;  // A p is no longer needed
  kern_.reduced_free_gradient(s_.x, s_.g, gr);
  const double g_gr = space_.dot(s_.g, gr);  // >= ||gr||^2
  if (!(g_gr > 0.0)) {                       // gr = 0: no free block left to move
    split_and_restart();
    return taken('e', a_f);
  }
  multiply(gr, Agr);
  const double grAgr = space_.dot(gr, Agr);
  if (!(grAgr > 0.0) || !std::isfinite(grAgr)) {
    return failed('e',
                  "expansion step: A is not positive definite along the reduced free gradient");
  }
  const double a = opt_.expansion_length_factor * g_gr / grAgr;
  if (a <= kern_.max_feasible_step(s_.x, gr)) {
    s_.x.noalias() -= a * gr;
    s_.g.noalias() -= a * Agr;
    c_.project(s_.x);  // only removes rounding-level infeasibility
    s_.recursive = bb_;
  } else {
    s_.x_saved = s_.x;
    s_.g_saved = s_.g;
    s_.g_saved_exact = s_.g_exact;
    const double q_boundary = objective();
    s_.x.noalias() -= a * gr;
    c_.project(s_.x);
    refresh_gradient();
    if (objective() > q_boundary) {
      ++rep_.n_expansion_fallbacks;
      s_.x = s_.x_saved - abar_ * gr;
      s_.g = s_.g_saved - abar_ * Agr;
      s_.g_exact = s_.g_saved_exact;
      c_.project(s_.x);  // only removes rounding-level infeasibility
      s_.recursive = bb_;
    }
  }
  split_and_restart();
  return taken('e', a_f);
}

// MpgpExpansion::ProjectedCG (PERMON's "projcg"): the whole CG step x := P(x - a_cg p), past the
// boundary, then g recomputed (1 product). Should q increase, x and g are restored and the step
// is the Fixed one (1 more product). BarzilaiBorwein's trial length stays as it was (updated with
// p, it gave more products on the paper's brick).
MpgpStep Mpgp::projected_cg_expansion(double a_f, double a_cg) {
  s_.allocate_expansion_work();
  s_.x_saved = s_.x;
  s_.g_saved = s_.g;
  s_.g_saved_exact = s_.g_exact;
  const double q_before = objective();
  s_.x.noalias() -= a_cg * s_.p;
  c_.project(s_.x);
  refresh_gradient();
  if (objective() > q_before) {
    ++rep_.n_expansion_fallbacks;
    s_.x = s_.x_saved;
    s_.g = s_.g_saved;
    s_.g_exact = s_.g_saved_exact;
    return fixed_expansion(a_f);  // A p is still in s_.Ap
  }
  split_and_restart();
  return taken('e', a_cg);
}

// Lines 14-15: the proportioning step 14(b), a projected move along the whole gradient
// (1 product), and CG restarts from phi.
MpgpStep Mpgp::proportioning_step() {
  const std::optional<double> alpha = projected_gradient_move(s_.g);
  if (!alpha) {
    return failed('p',
                  "proportioning step: A is not positive definite along the projected "
                  "gradient direction");
  }
  split_and_restart();
  return taken('p', *alpha);
}

// The projected move x := P(x - a v) of the expansion (v = phi) and the proportioning step
// (v = g): of fixed length (Paper) or spectral (BarzilaiBorwein). Returns the length of the move
// along -v, or nothing if A is found not positive definite along it.
std::optional<double> Mpgp::projected_gradient_move(const Eigen::VectorXd& v) {
  if (bb_) return spectral_move(v);
  return fixed_length_move(v);
}

// x := P(x - alpha_bar v), monotone without a line search for alpha_bar <= 2/||A||, and g
// recomputed (1 product). Returns alpha_bar.
double Mpgp::fixed_length_move(const Eigen::VectorXd& v) {
  s_.x.noalias() -= abar_ * v;
  c_.project(s_.x);
  refresh_gradient();
  return abar_;
}

// The spectral move (docs/theory.md §4.3) along the projected direction d = P(x - a v) - x, a the
// current spectral length, v = g or phi (v is the gradient restricted to the blocks d may move, so
// g^T d = v^T d <= -||d||^2 / a < 0 for d != 0): x := x + t d with t = min(1, -g^T d / d^T A d),
// the exact minimiser of q on the segment [x, x + d] (which lies in Omega), g updated recursively;
// 1 product. Each block of d carries a rounding error of order eps ||x_i|| (a projection puts a
// point on a circle only to rounding) and g is large on active blocks (the normal forces), so
// g^T d can be trusted only below -eps sum_i ||g_i|| ||x_i|| (times kRoundingFactor). Near the
// solution it no longer is; then the move is the fixed-length one (also 1 product; counted in
// n_fallbacks). Returns t a (or alpha_bar), or nothing if A is not positive definite along d.
std::optional<double> Mpgp::spectral_move(const Eigen::VectorXd& v) {
  const double a = s_.spectral.length();
  Eigen::VectorXd& d = s_.p;
  d = s_.x - a * v;
  c_.project(d);
  d -= s_.x;
  const double gd = space_.dot(s_.g, d);
  if (!(gd < -kRoundingFactor * std::numeric_limits<double>::epsilon() *
                 kern_.rounding_scale(s_.x, s_.g))) {
    ++rep_.n_fallbacks;
    return fixed_length_move(v);
  }
  multiply(d, s_.Ap);
  const double dAd = space_.dot(d, s_.Ap);
  if (!(dAd > 0.0) || !std::isfinite(dAd)) return std::nullopt;
  const double t = std::min(1.0, -gd / dAd);
  s_.x.noalias() += t * d;
  s_.g.noalias() += t * s_.Ap;
  c_.project(s_.x);  // only removes rounding-level infeasibility (x + t d is a convex combination)
  s_.recursive = true;
  s_.spectral.update(space_.squared_norm(d), dAd, space_.squared_norm(s_.Ap));
  return t * a;
}

// Av := A v, counted in n_products.
void Mpgp::multiply(const Eigen::VectorXd& v, Eigen::VectorXd& Av) {
  A_(v, Av);
  ++rep_.n_products;
  FRICON_CHECK(Av.size() == v.size(),
               "operator returned a vector of size " << Av.size() << ", expected " << v.size());
}

// g := A x - b (1 product).
void Mpgp::refresh_gradient() {
  multiply(s_.x, s_.g);
  s_.g -= b_;
  s_.recursive = false;
  s_.g_exact = true;
}

// The split of g at x; CG restarts from phi, or its preconditioned image (line 15), when the next
// step takes a direction (next_direction).
void Mpgp::split_and_restart() {
  s_.split = kern_.split(s_.x, s_.g, s_.phi, s_.beta);
  s_.direction = MpgpState::Direction::Restart;
}

// The direction of the CG steps (§4.2): phi, or with a preconditioner M, z = M phi restricted to
// the face of x. phi vanishes off the face, so g^T z = phi^T M phi > 0: a descent direction.
const Eigen::VectorXd& Mpgp::cg_direction() {
  if (!opt_.preconditioner) return s_.phi;
  s_.z.resize(s_.phi.size());  // allocates once
  opt_.preconditioner(s_.phi, s_.z);
  FRICON_CHECK(s_.z.size() == s_.phi.size(), "preconditioner returned a vector of size "
                                                 << s_.z.size() << ", expected " << s_.phi.size());
  kern_.restrict_to_face(s_.x, s_.z);
  ++rep_.n_preconditioner;
  return s_.z;
}

// Line 3, ||g^P|| <= threshold, where BarzilaiBorwein first recomputes a recursive gradient
// (counted in n_refreshes); then the other ends of the iteration.
std::optional<Stop> Mpgp::stop_test() {
  const double threshold =
      opt_.adaptive_tolerance ? std::max(threshold_, opt_.adaptive_tolerance(s_.x)) : threshold_;
  if (s_.recursive && std::isfinite(s_.split.gp2) && norm_gp() <= threshold) {
    refresh_gradient();
    split_and_restart();  // the free set is the same, phi has changed
    s_.q_prev = objective();
    s_.q_prev_exact = true;
    ++rep_.n_refreshes;
  }
  const int done = steps();
  if (!std::isfinite(s_.split.gp2) || !std::isfinite(s_.q_prev)) {
    return Stop{QpTermination::NumericalFailure,
                fmt::format("non-finite gradient or objective after {} iterations", done)};
  }
  if (norm_gp() <= threshold) {
    return Stop{
        QpTermination::Converged,
        fmt::format("||g^P|| = {:.3e} <= {:.3e} after {} iterations", norm_gp(), threshold, done)};
  }
  if (s_.stopped) {
    return Stop{QpTermination::UserStopped,
                fmt::format("stopped by the monitor after {} iterations", done)};
  }
  if (done >= opt_.max_iterations) {
    return Stop{QpTermination::MaxIterations,
                fmt::format("reached max_iterations = {} with ||g^P|| / ||r|| = {:.3e} (target "
                            "{:.3e})",
                            opt_.max_iterations, norm_gp() / rep_.reference_norm,
                            threshold_ / rep_.reference_norm)};
  }
  return std::nullopt;
}

void Mpgp::count(char kind) {
  switch (kind) {
    case 'c':
      ++rep_.n_cg;
      break;
    case 'e':
      ++rep_.n_expansion;
      break;
    default:
      ++rep_.n_proportioning;
  }
}

// The point after a step of the given kind ('s' for the start): the monotonicity count, the
// history and the monitor.
void Mpgp::record(char kind, double alpha) {
  const MpgpIteration it{.iteration = steps(),
                         .step = kind,
                         .norm_gp = norm_gp(),
                         .norm_phi = std::sqrt(s_.split.phi2),
                         .norm_beta = std::sqrt(s_.split.beta2),
                         .alpha = alpha,
                         .objective = objective()};
  // With alpha_bar <= 2/||A|| no step increases q; count the increases beyond rounding.
  const double q_tolerance =
      1e-12 * std::max({std::abs(s_.q_prev), std::abs(it.objective), rep_.norm_b * x_scale_});
  // Compared only where both values of q are exact (§4.7: not after turned discs' returns).
  const bool comparable = kind != 's' && s_.q_prev_exact && s_.g_exact;
  if (comparable && it.objective > s_.q_prev + q_tolerance) ++rep_.n_objective_increases;
  s_.q_prev = it.objective;
  s_.q_prev_exact = s_.g_exact;
  if (opt_.record_history) rep_.history.push_back(it);
  if (opt_.monitor && !opt_.monitor(it)) s_.stopped = true;
}

void Mpgp::finish(const Stop& stop) {
  rep_.termination = stop.termination;
  rep_.message = stop.message;
  rep_.norm_gp = norm_gp();
  rep_.rel_gp = rep_.norm_gp / rep_.reference_norm;
  rep_.objective = objective();
}

// The checks of solve_mpgp's documentation.
void check_inputs(const Operator& A, const Eigen::VectorXd& b, const SeparableConstraints& c,
                  const MpgpOptions& opt, const Eigen::VectorXd& x) {
  opt.validate();
  c.validate();
  if (!A) throw InputError("solve_mpgp: the operator A is empty");
  const Index n = c.size();
  if (b.size() != n || x.size() != n) {
    throw InputError(fmt::format(
        "solve_mpgp: the constraints cover {} unknowns but b has {} and x has {} entries", n,
        b.size(), x.size()));
  }
  if (!b.allFinite()) throw InputError("solve_mpgp: b has non-finite entries");
  if (!x.allFinite()) throw InputError("solve_mpgp: the initial guess x has non-finite entries");
}

// b_R = 0 (b = 0 in particular): q(x) = x^T A x / 2 - b^T x >= 0 = q(0) on Omega, since there
// b^T x <= 0 (b_i <= 0 on the bounds, x_i >= 0; b = 0 on the discs that are not pinned and on the
// Free blocks), and 0 is feasible, so x = 0, checked by one product.
void solve_zero_rhs(const Operator& A, const Eigen::VectorXd& b, const SeparableConstraints& c,
                    const DualSpace& space, Eigen::VectorXd& x, MpgpReport& rep) {
  x.setZero();
  Eigen::VectorXd g(x.size());
  A(x, g);
  ++rep.n_products;
  FRICON_CHECK(g.size() == x.size(),
               "operator returned a vector of size " << g.size() << ", expected " << x.size());
  const double norm_A0 = space.norm(g);
  if (norm_A0 != 0.0) {
    rep.termination = QpTermination::NumericalFailure;
    rep.message = fmt::format("A 0 has norm {}: A is not linear", norm_A0);
    rep.norm_gp = rep.rel_gp = norm_A0;
    return;
  }
  g -= b;
  // At x = 0 a bound is active with g_i = -b_i >= 0, a disc is pinned or has g_i = 0, and so has
  // a Free block: g^P = b_R = 0.
  rep.norm_gp = space.norm(resisted_part(b, c));
  rep.rel_gp = rep.norm_gp;
  rep.objective = 0.0;
  rep.termination = QpTermination::Converged;
  rep.message = rep.norm_b == 0.0 ? "b = 0: the solution is x = 0"
                                  : "b_R = 0 (no constraint resists b): the solution is x = 0";
}

// ||A|| (given, or estimated by power iteration) and alpha_bar = step_factor / ||A||.
void set_step_length(const Operator& A, Index n, const MpgpOptions& opt, MpgpReport& rep) {
  if (opt.norm_A > 0.0) {
    rep.norm_A_used = opt.norm_A;
  } else {
    rep.norm_A_estimated = true;
    rep.norm_A_used = estimate_norm(A, n, opt.power_iterations, opt.power_tolerance,
                                    &rep.n_power_products, opt.vectors());
  }
  if (!(rep.norm_A_used > 0.0) || !std::isfinite(rep.norm_A_used)) {
    throw NumericalError(
        fmt::format("solve_mpgp: ||A|| = {} ({}); A must be symmetric positive definite (n = {})",
                    rep.norm_A_used, rep.norm_A_estimated ? "power iteration" : "given", n));
  }
  rep.alpha_bar_used = opt.step_factor / rep.norm_A_used;
}

}  // namespace

MpgpReport solve_mpgp(const Operator& A, const Eigen::VectorXd& b, const SeparableConstraints& c,
                      const MpgpOptions& opt, Eigen::VectorXd& x) {
  const Stopwatch watch;
  check_inputs(A, b, c, opt, x);
  MpgpReport rep;
  rep.variant = opt.variant;
  rep.expansion = opt.expansion;
  rep.active_discs = opt.active_discs;
  const DualSpace& space = opt.vectors();
  rep.norm_b = space.norm(b);
  rep.reference_norm =
      opt.reference == StopReference::Whole ? rep.norm_b : space.norm(resisted_part(b, c));
  if (rep.reference_norm == 0.0) {
    solve_zero_rhs(A, b, c, space, x, rep);
  } else {
    set_step_length(A, c.size(), opt, rep);
    c.project(x);  // line 1: start from the projection of the initial guess
    Mpgp(A, b, c, opt, rep, x).run();
  }
  rep.iterations = rep.n_cg + rep.n_expansion + rep.n_proportioning;
  rep.seconds = watch.seconds();
  return rep;
}

}  // namespace fricon::qp
