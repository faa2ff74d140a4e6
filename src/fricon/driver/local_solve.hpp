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
#include <utility>
#include <vector>

#include "fricon/outer/outer_loop.hpp"
#include "fricon/qp/local_problem.hpp"
#include "fricon/qp/mpgp.hpp"
#include "fricon/qp/scaling.hpp"

namespace fricon::driver {

struct LocalSolveOptions {
  Real qp_rtol = 1e-10;  ///< each QP to ||g^P|| <= qp_rtol ||q|| (of the scaled QP: D g^P, D q)
  int qp_max = 100000;   ///< QP iterations per step
  /// Successive approximations: relative change of the normal reactions (Coulomb), or of all
  /// reactions when W is split (Coulomb or Tresca), at which they stop.
  Real outer_tol = 1e-10;
  int outer_max = 200;
  qp::MpgpVariant variant = qp::MpgpVariant::BarzilaiBorwein;
  /// MPGP's expansion move. Default ProjectedCG: with bb the fewest products on the QPs of graded
  /// meshes and of the paper's brick (qp::MpgpExpansion, bench/expansion_bench.cpp).
  qp::MpgpExpansion expansion = qp::MpgpExpansion::ProjectedCG;
  /// What MPGP's CG steps do with active discs. Default Turned, as in `fricon solve`
  /// (qp::MpgpDiscFace, theory.md §4.7).
  qp::MpgpDiscFace active_discs = qp::MpgpDiscFace::Turned;
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
  /// W counts as symmetric when max|W_ij - W_ji| <= symmetry_tol max|W_ij| (the round-off of the
  /// code that wrote it); a larger asymmetry is solved by the splitting W = S + A.
  Real symmetry_tol = 1e-13;
};

/// How far W is from symmetric: max|W_ij - W_ji| and max|W_ij|, both in W's unit.
struct Asymmetry {
  Real max_difference = 0.0;  ///< max over i, j of |W_ij - W_ji|
  Real max_entry = 0.0;       ///< max over i, j of |W_ij|
  /// max_difference / max_entry (0 for W = 0).
  Real relative() const { return max_entry > 0.0 ? max_difference / max_entry : 0.0; }
};

/// The asymmetry of a square W (InputError if W is not square).
Asymmetry measure_asymmetry(const SparseMatrix& W);

struct LocalSolution {
  bool solved = false;
  std::string reason;  ///< why not, when not solved
  VectorXd r, u;       ///< reactions and velocities u = W r + q
  int outer_iterations = 0;
  long qp_iterations = 0, n_products = 0;
  Real residual = 0.0;       ///< natural-map residual, relative (qp::coulomb_residual)
  Real merit = 0.0;          ///< LocalSolveOptions::merit of the answer (0 without one)
  int refinements = 0;       ///< re-solves with tighter tolerances that were needed
  Real norm_W = 0.0;         ///< power-method estimate of ||S||, S = (W + W^T)/2 (= W if symmetric)
  Real norm_W_scaled = 0.0;  ///< ... of ||D S D||, the matrix MPGP saw (norm_W without scaling)
  Asymmetry asymmetry;       ///< of W as given
  /// W is not symmetric (LocalSolveOptions::symmetry_tol): solved by the splitting W = S + A, each
  /// step's QP with Hessian S and A r of the previous step in q.
  bool split = false;
  Real norm_A = 0.0;  ///< power-method estimate of ||A||, A = (W - W^T)/2 (0 when not split)
  /// Observed contraction ratio of the outer iterations (outer::OuterReport; 0 if fewer than 3).
  Real contraction = 0.0;
  /// The last relative change of each block of the successive approximations' state ("r_n" for
  /// Coulomb, "A r" when W is split), in the order of the state; empty for one Tresca QP.
  std::vector<std::pair<std::string, Real>> last_changes;
  double seconds = 0.0;
  outer::OuterTermination termination = outer::OuterTermination::Converged;
};

/// The change of variables r = D y of LocalSolveOptions::scaling, on the layout
/// qp::SeparableConstraints::contact_layout(n_contacts): per contact a, on its bound and its disc
/// alike, d_a = 1 / sqrt(mean of W_3a,3a, W_3a+1,3a+1, W_3a+2,3a+2) [sqrt of 1 / W's unit], or 1
/// where that mean is not positive or not finite. diagonal_of_W: the m = 3 n_contacts diagonal
/// entries of W (m a multiple of 3, else InputError).
qp::BlockScaling contact_scaling(const VectorXd& diagonal_of_W);

/// W's symmetry as one line of a summary: "symmetric (max|W - W^T| = ..., max|W| = ...)", or, for
/// a split W, the same numbers, ||A||/||S|| and the last relative change of A r.
std::string describe_symmetry(const LocalSolution& s);

/// Solves the problem. Throws InputError for an inconsistent problem (sizes, negative
/// coefficients or thresholds, non-finite entries).
LocalSolution solve_local(const qp::LocalProblem& problem, const LocalSolveOptions& options = {});

}  // namespace fricon::driver
