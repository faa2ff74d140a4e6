#pragma once
// qp (internal to mpgp.cpp): the block-wise kernels of MPGP and the spectral step length.
//
//   Kernels::split              the gradient split g^P = phi + beta and its norms (docs/theory.md
//                               §4.1)
//   Kernels::reduced_free_gradient  the vector phitilde_{alpha_bar} (the Optimal expansion's
//                               direction)
//   Kernels::rounding_scale     the rounding level of g^T d for a projected direction d
//   Kernels::max_feasible_step  the longest feasible step along -p (the CG step's a_f)
//   Kernels::restrict_to_face   a vector restricted to the face (preconditioning in face; the
//                               turned discs' tangents, MpgpDiscFace::Turned)
//   Kernels::turn_curvature     the turned discs' circle curvature along a direction (§4.7)
//   SpectralLength              the Barzilai-Borwein trial length of the bb variant (§4.3)

#include <array>
#include <vector>

#include <Eigen/Core>

#include "fricon/core/types.hpp"
#include "fricon/qp/constraints.hpp"
#include "fricon/qp/dual_space.hpp"
#include "fricon/qp/mpgp.hpp"

namespace fricon::qp::detail {

/// Scalars of the gradient split at one point (docs/theory.md §4.1).
struct Split {
  double gp2 = 0.0;    ///< ||g^P||^2
  double phi2 = 0.0;   ///< ||phi||^2
  double beta2 = 0.0;  ///< ||beta||^2
  /// phitilde_{alpha_bar}^T phi, the right-hand side of the proportionality test (§4.2)
  double phit_phi = 0.0;
};

/// Block-wise kernels of MPGP for fixed constraints and tolerances. With MpgpDiscFace::Turned
/// they remember which active discs the last split() turned (docs/theory.md §4.7); the other
/// kernels then take the x of that split.
class Kernels {
 public:
  /// The kernels of `c`, this process's blocks of the unknowns in `space`: the scalars they
  /// return (norms, sums, the feasible step, whether a disc turned) are those of the whole, and
  /// every call that returns one is collective there.
  Kernels(const SeparableConstraints& c, double tol_bound, double tol_disc, double alpha_bar,
          MpgpDiscFace active_discs, const DualSpace& space = whole_space())
      : c_(c),
        space_(space),
        tol_bound_(tol_bound),
        tol_disc_(tol_disc),
        alpha_bar_(alpha_bar),
        turn_limit_(active_discs == MpgpDiscFace::Turned ? kTurnCurvature / alpha_bar : -1.0),
        turned_(c.blocks.size(), 0) {}

  /// Fills phi (free gradient) and beta (chopped gradient) for g at x and returns the norms.
  /// Active: Bound x_i <= tol_bound; Disc ||x_i|| >= (1 - tol_disc) rho_i (always for rho_i = 0,
  /// whose gradient parts are all 0); Free never (phi_i = g_i). An active disc is turned
  /// (MpgpDiscFace::Turned, rho_i > 0 and mu_i / rho_i within the limit, mu_i the outward
  /// normal force max(-eta_i^T g_i, 0)): phi_i is the tangential part of g_i, beta_i its inward
  /// normal part.
  Split split(const Eigen::VectorXd& x, const Eigen::VectorXd& g, Eigen::VectorXd& phi,
              Eigen::VectorXd& beta);

  /// True if the last split() turned some disc (of any process).
  bool turns_discs() const { return any_turned_; }

  /// Fills gr with the reduced free gradient phitilde_{alpha_bar}(x) = (x - P(x - alpha_bar
  /// phi)) / alpha_bar for g at x (docs/theory.md §4.1), with the active sets of split(): 0 on
  /// active blocks, turned discs included; x - t gr is feasible for t in [0, alpha_bar] and
  /// g^T gr >= ||gr||^2.
  void reduced_free_gradient(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                             Eigen::VectorXd& gr) const;

  /// Sum over the blocks of ||g_i|| ||x_i||: the scale of the rounding error of g^T d for a
  /// projected direction d (each d_i is exact only to about eps ||x_i||).
  double rounding_scale(const Eigen::VectorXd& x, const Eigen::VectorXd& g) const;

  /// Largest t >= 0 with x - t p in Omega (+inf if no block restricts; Free blocks never do,
  /// nor do turned discs, which return to their circles after the step: p must not move them
  /// off their tangents); x must be feasible up to rounding.
  double max_feasible_step(const Eigen::VectorXd& x, const Eigen::VectorXd& p) const;

  /// Clears v on the blocks that split() finds held active at x (and on pinned discs), and
  /// keeps only the tangential part of v on turned discs: v restricted to the face of x, where
  /// the CG steps move (docs/theory.md §4.2, §4.7).
  void restrict_to_face(const Eigen::VectorXd& x, Eigen::VectorXd& v) const;

  /// Clears v on every active block, turned discs included (the face of MpgpDiscFace::Held,
  /// along which a projected move descends).
  void clear_active(const Eigen::VectorXd& x, Eigen::VectorXd& v) const;

  /// p^T D p, D the turned discs' circle curvature at x for the gradient g: mu_i / rho_i on each
  /// turned disc's tangent, 0 elsewhere; Dp := D p. q along the circles is, to second order,
  /// that of A + D (docs/theory.md §4.7).
  double turn_curvature(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                        const Eigen::VectorXd& p, Eigen::VectorXd& Dp) const;

 private:
  bool turned(std::size_t k) const { return turned_[k] != 0; }
  /// The split's sums, and whether a disc turned, over the processes (n_turned_ is this one's).
  Split reduced(Split s);
  /// restrict_to_face (keep_tangents) or clear_active (not).
  void restrict(const Eigen::VectorXd& x, Eigen::VectorXd& v, bool keep_tangents) const;

  const SeparableConstraints& c_;
  const DualSpace& space_;
  double tol_bound_;
  double tol_disc_;
  double alpha_bar_;
  double turn_limit_;         ///< mu_i / rho_i of the tightest turned circle (< 0: Held)
  std::vector<char> turned_;  ///< per block: the last split() turned this active disc
  std::size_t n_turned_ = 0;  ///< how many it turned here
  bool any_turned_ = false;   ///< it turned some on some process
};

/// The adaptive Barzilai-Borwein length "ABBmin" (Frassoldati, Zanghirati and Zanni, 2008) of
/// the spectral moves (docs/theory.md §4.3): after a step s with y = A s, the long length
/// a1 = s^T s / s^T y and the short one a2 = s^T y / y^T y (a2 <= a1, both in
/// [1/||A||, 1/lambda_min]); the next length is the smallest a2 of the last kMemory steps when
/// a2 / a1 < kTau (the step was dominated by large eigenvalues), else a1. Clamped to [lo, hi].
/// kTau = 0.2 gave the fewest products on the paper's problems among 0.1, 0.2, 0.3 and 0.5
/// (bench/qp_variants_bench.cpp); the memory 2 ... 5 hardly matters.
class SpectralLength {
 public:
  SpectralLength(double initial, double lo, double hi) : length_(initial), lo_(lo), hi_(hi) {}

  double length() const { return length_; }

  /// The last step through s^T s, s^T A s and (A s)^T (A s); a common positive factor cancels,
  /// so a direction d and its multiple t d give the same lengths. A step without positive
  /// curvature (or non-finite values) keeps the current length.
  void update(double ss, double sy, double yy);

 private:
  static constexpr int kMemory = 3;
  static constexpr double kTau = 0.2;
  double length_;
  double lo_, hi_;
  std::array<double, kMemory> short_{};
  int count_ = 0;
};

}  // namespace fricon::qp::detail
