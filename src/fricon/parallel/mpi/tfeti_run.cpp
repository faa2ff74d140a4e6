// parallel/mpi: backend "tfeti" on the ranks of an MPI job (docs/parallel.md, "Total FETI on
// ranks"; docs/theory.md §8.8). Every rank runs driver::run on the same problem; the subdomains
// are shared out by MpiRanks, which the run's FETI operator uses for its sums, and whose agreed
// stop request replaces the rank's own.
#include <algorithm>
#include <thread>

#include "fricon/core/error.hpp"
#include "fricon/linalg/blas.hpp"
#include "fricon/parallel/distributed_run.hpp"
#include "fricon/parallel/mpi/feti_ranks.hpp"
#include "fricon/parallel/mpi/session.hpp"
#include "fricon/parallel/mpi/test_fault.hpp"

namespace fricon::parallel {

namespace {

// The ranks of `comm` on this node (sharing its memory and cores).
int ranks_on_this_node(MPI_Comm comm) {
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int n = 1;
  MPI_Comm_size(node, &n);
  MPI_Comm_free(&node);
  return n;
}

// The threads of this rank's subdomain loops: the run's, at most its share of the node's cores.
int threads_per_rank(MPI_Comm comm) {
  const int cores = static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
  return std::max(1, std::min(linalg::threads(), cores / ranks_on_this_node(comm)));
}

// In a catch block of the run: an error the ranks cannot all have raised at this point ends the
// job; an agreed one (a step's agreement, or the stop they agreed on) passes.
void end_unless_shared(const MpiRanks& ranks) {
  if (!ranks.joined()) ranks.fail_before_joining(std::current_exception());
  try {
    throw;
  } catch (const Interrupted& e) {
    if (ranks.agreed_stop()->load()) throw AgreedError<Interrupted>(e.what());
  } catch (...) {
  }
  abort_unless_agreed(world());
}

}  // namespace

driver::RunResult run_tfeti_on_ranks(const driver::Problem& problem,
                                     const driver::RunOptions& options) {
  if (!launched_by_mpi()) return driver::run(problem, options);
  initialize();
  const MpiRanks ranks(world(), options.stop_requested);
  driver::RunOptions on_ranks = options;
  on_ranks.stop_requested = ranks.agreed_stop();
  on_ranks.feti_ranks = &ranks;
  const linalg::KeepThreads run_threads;
  linalg::set_threads(threads_per_rank(world()));
  driver::RunResult r;
  try {
    test_fault("model");  // (a failure before the ranks' first step together)
    r = driver::run(problem, on_ranks);
    ranks.join();
  } catch (...) {
    end_unless_shared(ranks);
    throw;
  }
  return r;
}

}  // namespace fricon::parallel
