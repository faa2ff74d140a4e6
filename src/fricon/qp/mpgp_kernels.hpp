#pragma once
// qp (internal to mpgp.cpp): the block-wise kernels of MPGP and the spectral step length.
//
//   Kernels::split              the gradient split g^P = phi + beta and its norms (docs/theory.md
//                               §4.1)
//   Kernels::reduced_free_gradient  the vector phitilde_{alpha_bar} (the Optimal expansion's
//                               direction)
//   Kernels::rounding_scale     the rounding level of g^T d for a projected direction d
//   Kernels::max_feasible_step  the longest feasible step along -p (the CG step's a_f)
//   Kernels::restrict_to_face   a vector with the active blocks cleared (preconditioning in face)
//   SpectralLength              the Barzilai-Borwein trial length of the bb variant (§4.3)

#include <array>

#include <Eigen/Core>

#include "fricon/core/types.hpp"
#include "fricon/qp/constraints.hpp"

namespace fricon::qp::detail {

/// Scalars of the gradient split at one point (docs/theory.md §4.1).
struct Split {
  double gp2 = 0.0;    ///< ||g^P||^2
  double phi2 = 0.0;   ///< ||phi||^2
  double beta2 = 0.0;  ///< ||beta||^2
  /// phitilde_{alpha_bar}^T phi, the right-hand side of the proportionality test (§4.2)
  double phit_phi = 0.0;
};

/// Block-wise kernels of MPGP for fixed constraints and tolerances.
class Kernels {
 public:
  Kernels(const SeparableConstraints& c, double tol_bound, double tol_disc, double alpha_bar)
      : c_(c), tol_bound_(tol_bound), tol_disc_(tol_disc), alpha_bar_(alpha_bar) {}

  /// Fills phi (free gradient) and beta (chopped gradient) for g at x and returns the norms.
  /// Active: Bound x_i <= tol_bound; Disc ||x_i|| >= (1 - tol_disc) rho_i (always for rho_i = 0,
  /// whose gradient parts are all 0); Free never (phi_i = g_i).
  Split split(const Eigen::VectorXd& x, const Eigen::VectorXd& g, Eigen::VectorXd& phi,
              Eigen::VectorXd& beta) const;

  /// Fills gr with the reduced free gradient phitilde_{alpha_bar}(x) = (x - P(x - alpha_bar
  /// phi)) / alpha_bar for g at x (docs/theory.md §4.1), with the active sets of split(): 0 on
  /// active blocks; x - t gr is feasible for t in [0, alpha_bar] and g^T gr >= ||gr||^2.
  void reduced_free_gradient(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                             Eigen::VectorXd& gr) const;

  /// Sum over the blocks of ||g_i|| ||x_i||: the scale of the rounding error of g^T d for a
  /// projected direction d (each d_i is exact only to about eps ||x_i||).
  double rounding_scale(const Eigen::VectorXd& x, const Eigen::VectorXd& g) const;

  /// Largest t >= 0 with x - t p in Omega (+inf if no block restricts; Free blocks never do); x
  /// must be feasible up to rounding.
  double max_feasible_step(const Eigen::VectorXd& x, const Eigen::VectorXd& p) const;

  /// Clears v on the blocks that split() finds active at x (and on pinned discs): v restricted
  /// to the face of x, where the preconditioned CG steps move (docs/theory.md §4.2).
  void restrict_to_face(const Eigen::VectorXd& x, Eigen::VectorXd& v) const;

 private:
  const SeparableConstraints& c_;
  double tol_bound_;
  double tol_disc_;
  double alpha_bar_;
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
