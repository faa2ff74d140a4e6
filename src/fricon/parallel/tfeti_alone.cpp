// parallel: backend "tfeti" in a fricon built without MPI (PETSc): the subdomains on this process
// alone. With PETSc, parallel/mpi/tfeti_run.cpp runs them on the ranks of the job. A file of its
// own, so that the readers' fuzz build (fuzz/CMakeLists.txt), which takes backend.cpp for the
// backend names, does not need the driver.
#ifndef FRICON_HAVE_PETSC
#include "fricon/parallel/distributed_run.hpp"

namespace fricon::parallel {

driver::RunResult run_tfeti_on_ranks(const driver::Problem& problem,
                                     const driver::RunOptions& options) {
  return driver::run(problem, options);
}

}  // namespace fricon::parallel
#endif
