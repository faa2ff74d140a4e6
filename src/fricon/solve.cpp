#include "fricon/solve.hpp"

#include "fricon/parallel/distributed_run.hpp"

namespace fricon {

driver::RunResult solve(const driver::Problem& problem, const driver::RunOptions& options) {
  switch (problem.solver.backend) {
    case parallel::Backend::Cholmod:
      return driver::run(problem, options);
    case parallel::Backend::Tfeti:
      return parallel::run_tfeti_on_ranks(problem, options);
    case parallel::Backend::Petsc:
      // Validated on every rank there; a build without PETSc says here how to get it.
      if (!parallel::petsc_available()) driver::validate(problem);
      return parallel::run_distributed(problem, options);
  }
  driver::validate(problem);  // an enum value outside its table: named by validate()
  throw Error("fricon::solve: invalid solver.backend");
}

}  // namespace fricon
