#pragma once
// parallel: the run of a problem on the ranks of an MPI job ([solver] backend = "petsc";
// docs/parallel.md, docs/theory.md §3.3). Implemented in parallel/mpi/ when fricon is built with
// PETSc; without it, validate() has already refused the backend.

#include "fricon/driver/run.hpp"

namespace fricon::parallel {

/// driver::run on every rank of MPI_COMM_WORLD (started here if it is not yet: a process not
/// launched by mpirun is a job of one rank). Collective: every rank calls it with the same
/// problem. Every rank builds the mesh and the loads, assembles K from its own tetrahedra
/// (solver.partition) and gives the entries to one MUMPS factorization; rank 0 runs the dual
/// QPs and the outer loop on Q and returns the whole result, the same as driver::run's. The
/// other ranks serve rank 0's solves and return a result whose report holds only the status
/// (and report.parallel->rank). An error on any rank is thrown on every rank, the same, or,
/// where the ranks cannot agree on it (a rank failing inside a step of collective calls), the
/// failing rank prints it and ends the job: MPI_Abort, exit code 3 (docs/parallel.md, "When a
/// rank fails").
driver::RunResult run_distributed(const driver::Problem& problem,
                                  const driver::RunOptions& options);

/// Backend "tfeti" under mpirun (docs/parallel.md, "Total FETI on ranks"): driver::run on every
/// rank of MPI_COMM_WORLD, the subdomains shared out in blocks (parallel/mpi/feti_ranks.hpp),
/// each rank factoring its own and holding its share of the multipliers in the QPs (theory.md
/// §8.8). Collective. Every rank returns the whole result (rank 0 writes it). An error that every
/// rank raises (bad input, a subdomain that cannot be factored, a stop) ends every rank the same;
/// one rank failing alone in a step of collective calls ends the job (MPI_Abort, exit code 3).
/// Threads per rank: the run's, at most the cores of the node shared by the ranks on it. A
/// process not started by mpirun (or a fricon built without MPI) runs driver::run alone.
driver::RunResult run_tfeti_on_ranks(const driver::Problem& problem,
                                     const driver::RunOptions& options);

}  // namespace fricon::parallel
