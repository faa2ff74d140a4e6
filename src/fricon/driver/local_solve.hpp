#pragma once
// driver: a local frictional contact problem of another code (qp/local_problem.hpp) solved the
// way fricon solves its own (theory.md §5.6): Tresca by one QP (MPGP), Coulomb by successive
// approximations over Tresca QPs on the normal reactions, warm-started, from the frictionless
// problem. Every answer is certified by the natural-map residual of the problem; a run that does
// not reach its tolerance says why (the QP did not converge, e.g. because W is singular; the
// successive approximations do not contract), never returns a half answer as solved.

#include <functional>
#include <string>

#include "fricon/outer/outer_loop.hpp"
#include "fricon/qp/local_problem.hpp"
#include "fricon/qp/mpgp.hpp"

namespace fricon::driver {

struct LocalSolveOptions {
  Real qp_rtol = 1e-10;    ///< each QP to ||g^P|| <= qp_rtol ||q||
  int qp_max = 100000;     ///< QP iterations per step
  Real outer_tol = 1e-10;  ///< Coulomb: relative change of the normal reactions
  int outer_max = 200;
  qp::MpgpVariant variant = qp::MpgpVariant::BarzilaiBorwein;
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
  Real residual = 0.0;  ///< natural-map residual, relative (qp::coulomb_residual)
  Real merit = 0.0;     ///< LocalSolveOptions::merit of the answer (0 without one)
  int refinements = 0;  ///< re-solves with tighter tolerances that were needed
  Real norm_W = 0.0;    ///< power-method estimate
  double seconds = 0.0;
  outer::Termination termination = outer::Termination::Converged;
};

/// Solves the problem. Throws InputError for an inconsistent problem (sizes, negative
/// coefficients or thresholds, non-finite entries).
LocalSolution solve_local(const qp::LocalProblem& problem, const LocalSolveOptions& options = {});

}  // namespace fricon::driver
