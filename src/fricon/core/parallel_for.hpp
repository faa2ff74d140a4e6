#pragma once
// core: a loop over independent items on a few threads (the subdomains of Total FETI,
// theory.md §8.4): each thread takes the next item from a shared counter, so that items of unequal
// cost balance themselves.

#include <functional>

#include "fricon/core/types.hpp"

namespace fricon {

/// Calls body(i, thread) for every i in [0, n), on `threads` threads (the calling thread is
/// thread 0; threads <= 1 runs the loop on it alone). thread is in [0, threads), so that a body
/// may accumulate into per-thread storage. The first exception a body throws is rethrown once
/// every thread has stopped (the others stop taking items).
void parallel_for(Index n, int threads, const std::function<void(Index i, int thread)>& body);

/// The threads of a loop: `requested` if > 0, else the machine's cores
/// (std::thread::hardware_concurrency, at least 1).
int loop_threads(int requested);

}  // namespace fricon
