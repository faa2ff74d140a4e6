#pragma once
// driver: a local frictional contact problem of another code (qp/local_problem.hpp) solved the
// way fricon solves its own (theory.md §5.6): Tresca by one QP (MPGP), Coulomb by successive
// approximations over Tresca QPs on the normal reactions, warm-started, from the frictionless
// problem. Each QP is solved in variables scaled per contact (qp/scaling.hpp), so that contacts
// whose blocks of W lie orders of magnitude apart do not spread the spectrum MPGP sees; the
// reactions, velocities and residuals are those of the problem as given. Every answer is
// certified by the natural-map residual of the problem; a run that does not reach its tolerance
// says why (the QP did not converge, e.g. because W is singular; the successive approximations
// do not contract), never returns a half answer as solved.

#include <functional>
#include <string>

#include "fricon/outer/outer_loop.hpp"
#include "fricon/qp/local_problem.hpp"
#include "fricon/qp/mpgp.hpp"
#include "fricon/qp/scaling.hpp"

namespace fricon::driver {

struct LocalSolveOptions {
  Real qp_rtol = 1e-10;    ///< each QP to ||g^P|| <= qp_rtol ||q|| (of the scaled QP: D g^P, D q)
  int qp_max = 100000;     ///< QP iterations per step
  Real outer_tol = 1e-10;  ///< Coulomb: relative change of the normal reactions
  int outer_max = 200;
  qp::MpgpVariant variant = qp::MpgpVariant::BarzilaiBorwein;
  /// MPGP's expansion move. Default ProjectedCG: with bb the fewest products on the QPs of graded
  /// meshes and of the paper's brick (qp::MpgpExpansion, bench/expansion_bench.cpp).
  qp::MpgpExpansion expansion = qp::MpgpExpansion::ProjectedCG;
  /// Solve each QP for y = D^-1 r with one factor per contact, d_a = 1 / sqrt(mean of the
  /// diagonal of contact a's 3 x 3 block of W) (1 where that mean is not positive): the scaled W
  /// has a diagonal of about 1. The QP's relative tolerance then refers to the scaled problem;
  /// the answer and its certificate do not change meaning. Default true.
  bool scaling = true;
  /// The answer counts as solved when its natural-map residual (relative) is at most this...
  Real residual_tol = 1e-8;
  /// ... and, if given, another code's merit function of (r, u) too (e.g. FCLIB's): at most
  /// merit_tol. While it is above, the solve is refined (QP and outer tolerances divided by 100,
  /// warm-started) up to `refinements` times.
  std::function<Real(const VectorXd& r, const VectorXd& u)> merit;
  Real merit_tol = 1e-8;
  int refinements = 2;
};

struct LocalSolution {
  bool solved = false;
  std::string reason;  ///< why not, when not solved
  VectorXd r, u;       ///< reactions and velocities u = W r + q
  int outer_iterations = 0;
  long qp_iterations = 0, n_products = 0;
  Real residual = 0.0;       ///< natural-map residual, relative (qp::coulomb_residual)
  Real merit = 0.0;          ///< LocalSolveOptions::merit of the answer (0 without one)
  int refinements = 0;       ///< re-solves with tighter tolerances that were needed
  Real norm_W = 0.0;         ///< power-method estimate of ||W||
  Real norm_W_scaled = 0.0;  ///< ... of ||D W D||, the matrix MPGP saw (norm_W without scaling)
  double seconds = 0.0;
  outer::Termination termination = outer::Termination::Converged;
};

/// The change of variables r = D y of LocalSolveOptions::scaling, on the layout
/// qp::SeparableConstraints::contact_layout(n_contacts): per contact a, on its bound and its disc
/// alike, d_a = 1 / sqrt(mean of W_3a,3a, W_3a+1,3a+1, W_3a+2,3a+2) [sqrt of 1 / W's unit], or 1
/// where that mean is not positive or not finite. diagonal_of_W: the m = 3 n_contacts diagonal
/// entries of W (m a multiple of 3, else InputError).
qp::BlockScaling contact_scaling(const VectorXd& diagonal_of_W);

/// Solves the problem. Throws InputError for an inconsistent problem (sizes, negative
/// coefficients or thresholds, non-finite entries).
LocalSolution solve_local(const qp::LocalProblem& problem, const LocalSolveOptions& options = {});

}  // namespace fricon::driver
