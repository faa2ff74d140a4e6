#pragma once
// fricon::solve, the entry point above the two ways a problem runs: on one process
// (driver::run, CHOLMOD) or on the ranks of an MPI job (parallel::run_distributed, MUMPS), as
// [solver] backend chooses. The program, the Python module and code that does not care where K
// is factored call this; the stages below it never call back up.

#include "fricon/driver/run.hpp"

namespace fricon {

/// Runs `problem` where solver.backend says: driver::run for "cholmod",
/// parallel::run_distributed for "petsc" (collective over MPI_COMM_WORLD; a fricon built without
/// PETSc refuses it with an InputError saying how to get it), parallel::run_tfeti_on_ranks for
/// "tfeti" (on the ranks of MPI_COMM_WORLD under mpirun, else driver::run). Returns what they
/// return.
driver::RunResult solve(const driver::Problem& problem, const driver::RunOptions& options = {});

}  // namespace fricon
