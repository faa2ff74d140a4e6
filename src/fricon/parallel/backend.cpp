#include "fricon/parallel/backend.hpp"

namespace fricon::parallel {

bool petsc_available() {
#ifdef FRICON_HAVE_PETSC
  return true;
#else
  return false;
#endif
}

}  // namespace fricon::parallel

#ifndef FRICON_HAVE_PETSC
#include "fricon/core/error.hpp"
#include "fricon/parallel/distributed_run.hpp"

namespace fricon::parallel {

driver::RunResult run_distributed(const driver::Problem&, const driver::RunOptions&) {
  throw InputError("solver.backend = \"petsc\": this fricon was built without PETSc");
}

}  // namespace fricon::parallel
#endif
