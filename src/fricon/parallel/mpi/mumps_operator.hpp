#pragma once
// parallel/mpi: the dual operator of a distributed run (docs/theory.md §3.3), on rank 0:
//   schur     Q = -S, the Schur complement MUMPS returns from the factorization of the augmented
//             matrix; products are dense
//   implicit  K factored alone; each product with Q is one distributed solve (for a Q too large
//             to form)
// In both the displacement is a distributed solve (DistributedSolves), on the contact dofs inside
// the outer loop. Both implement dual::DualOperator, so the outer loop runs on them exactly as on
// CHOLMOD's.

#include <memory>

#include "fricon/dual/dual_operator.hpp"
#include "fricon/parallel/mpi/distributed_solves.hpp"

namespace fricon::parallel {

/// Rank 0: the operator of `kind` (Schur or Implicit) on `solves` (whose factor was built with
/// the multipliers as Schur variables for Schur, K alone for Implicit), for B (n_dual x n_free)
/// [m^2] and the constant part c of the constraints (offset, or null). Its solves are collective
/// with the other ranks' DistributedSolves::follow(). References must outlive the operator.
std::unique_ptr<dual::DualOperator> make_mumps_operator(dual::DualOperatorKind kind,
                                                        const DistributedSolves& solves,
                                                        const MatrixXd* schur,
                                                        const SparseMatrix& B,
                                                        const VectorXd* offset);

}  // namespace fricon::parallel
