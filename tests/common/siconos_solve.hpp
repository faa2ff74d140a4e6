#pragma once
// Siconos numerics' solvers on a local frictional contact problem (u = W r + q, the Coulomb cone
// of coefficient mu per contact, normal component first): shared by the Siconos verification
// tests (tests/verification/siconos) and bench/fclib_compare.cpp. Header only, and only for the
// targets that link Siconos (fricon_siconos, cmake/dependencies.cmake).
#include "FrictionContactProblem.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"
#include "NumericsMatrix.h"
#include "SolverOptions.h"
#include "fricon/core/timer.hpp"
#include "fricon/core/types.hpp"

namespace fricon::test {

struct SiconosSolution {
  VectorXd r;          ///< the reactions
  int info = 0;        ///< fc3d_driver's value: 0 when the solver met its tolerance
  int iterations = 0;  ///< the solver's own count (SICONOS_IPARAM_ITER_DONE)
  double seconds = 0;  ///< the time of fc3d_driver alone
};

/// Siconos' `solver` (e.g. SICONOS_FRICTION_3D_NSN_AC) from r = 0 on the problem (W dense, 3 rows
/// per contact), with its default options but the tolerance `tol` on its own error and at most
/// `max_iterations` iterations.
inline SiconosSolution siconos_solve(const MatrixXd& W, const VectorXd& q, const VectorXd& mu,
                                     int solver, double tol, int max_iterations) {
  const int n = static_cast<int>(q.size());
  NumericsMatrix* M = NM_create(NM_DENSE, n, n);
  Eigen::Map<MatrixXd>(M->matrix0, n, n) = W;
  VectorXd q_copy = q, mu_copy = mu;  // Siconos takes non-const pointers
  FrictionContactProblem fcp{};
  fcp.dimension = 3;
  fcp.numberOfContacts = n / 3;
  fcp.M = M;
  fcp.q = q_copy.data();
  fcp.mu = mu_copy.data();
  SolverOptions* o = solver_options_create(solver);
  o->dparam[SICONOS_DPARAM_TOL] = tol;
  o->iparam[SICONOS_IPARAM_MAX_ITER] = max_iterations;
  SiconosSolution s;
  s.r = VectorXd::Zero(n);
  VectorXd u = VectorXd::Zero(n);
  const Stopwatch watch;
  s.info = fc3d_driver(&fcp, s.r.data(), u.data(), o);
  s.seconds = watch.seconds();
  s.iterations = o->iparam[SICONOS_IPARAM_ITER_DONE];
  solver_options_delete(o);
  NM_free(M);
  return s;
}

}  // namespace fricon::test
