#pragma once
// driver: how a caller follows a run (progress callbacks, a stop request) and what it reports of
// each outer iteration. Every stage of a run takes these options; fricon::solve passes them on.

#include <atomic>
#include <functional>
#include <string>

#include "fricon/core/types.hpp"
#include "fricon/qp/mpgp.hpp"

namespace fricon::feti {
class Ranks;
}

namespace fricon::driver {

struct RunResult;

/// What a run reports of one outer iteration (a Tresca problem with a frozen coefficient) and
/// its QP; outer::OuterIteration is the loop's own record of it.
struct IterationReport {
  int k = 0;
  Real err = 0.0;         ///< err(k) = ||phi^k - phi^(k-1)|| / ||phi^k|| (theory.md §5.2)
  int qp_iterations = 0;  ///< MPGP steps
  long qp_products = 0;   ///< products with Q in this QP (n_mult contribution)
  Real qp_rel_gp = 0.0;   ///< final ||g^P|| / ||h||
  qp::QpTermination qp_termination = qp::QpTermination::Converged;
  int n_objective_increases = 0;  ///< MPGP steps that increased the objective (expected 0)
  double seconds = 0.0;           ///< wall time of this outer iteration [s]
};

/// How a run reports progress and what it keeps besides the solution.
struct RunOptions {
  /// Keep the dual problem of the first outer iteration (ContactOutcome::first_dual).
  bool keep_first_dual = false;
  /// Called after every outer iteration (the monitor line of `fricon solve`).
  std::function<void(const IterationReport&)> on_outer_iteration;
  /// Called after every MPGP step of every QP (verbose progress); return false to stop.
  std::function<bool(const qp::MpgpIteration&)> on_qp_iteration;
  /// Called when a phase starts ("assembly", "factorize", ...) so that long phases are visible;
  /// on the ranks other than 0 of a distributed run, "follow" when they start serving rank 0's
  /// outer loop.
  std::function<void(const std::string& phase)> on_phase_start;
  /// Called after every step of a loading path with the step's result (its report's last
  /// entry of `steps` describes it), converged or not, before the next step starts; a stop
  /// requested by the time it returns ends the path there (run_path).
  std::function<void(const RunResult& step)> on_step;
  /// If set and true, the run stops at the next QP step (e.g. set by a SIGINT handler) and
  /// returns what it has, not converged; while Q is formed it throws fricon::Interrupted.
  const std::atomic<bool>* stop_requested = nullptr;
  /// Backend "tfeti": the processes that share the subdomains (feti/ranks.hpp), every one of
  /// them running this run the same; null: this process alone (parallel/tfeti_run.hpp sets it
  /// under mpirun).
  const feti::Ranks* feti_ranks = nullptr;
  /// Whether the run computes the result's fields (the stresses): a process that neither writes
  /// nor reads them may go without (`fricon solve` on the ranks other than 0 of backend "tfeti"
  /// under mpirun, which write nothing). The status and the report are the same either way.
  bool fields = true;

  /// Whether a stop was requested (stop_requested is set and true).
  bool stop_was_requested() const { return stop_requested != nullptr && stop_requested->load(); }
};

}  // namespace fricon::driver
