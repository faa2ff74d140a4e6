#pragma once
// fricon (the program): Ctrl-C (SIGINT), SIGTERM and SIGUSR1 during a solve.
//
// Once the outer loop has started there is an iterate to save: a signal asks the run to stop at
// its next QP step (stop_requested, which the library polls), and the run writes its last
// iterate as not converged; a signal that arrives once the outer loop has converged leaves the
// converged, certified answer as it is (written as converged, exit code 0). Before the outer
// loop (assembly, factorization, forming Q: long library calls with nothing to save) the
// program ends at once with exit code 2 and no results. A second
// signal ends it at once in any case. Under mpirun (docs/parallel.md) SIGUSR1 is the one to
// send: mpirun forwards it to every rank, while on Ctrl-C it kills the ranks a second after
// SIGTERM; the ranks other than 0 ignore the first signal once they follow rank 0's outer loop,
// whose solves they serve until rank 0 has written its results.

#include <atomic>

namespace fricon::app {

/// Set by the first signal once has_iterate is set; the run polls it.
extern std::atomic<bool> stop_requested;
/// Set when the outer loop starts: from then on a signal stops the run instead of ending it.
extern std::atomic<bool> has_iterate;

void install_signal_handlers();

}  // namespace fricon::app
