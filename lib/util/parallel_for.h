#pragma once

// The project's one threading primitive: a parallel loop over independent items on std::threads.
// Items are handed out dynamically (an atomic counter), so uneven work balances; each item must write
// only its own outputs, which makes results independent of the thread count by construction.

#include <cstddef>
#include <functional>

namespace lutex {

// Number of threads to use for `requested`: values <= 0 mean "all hardware threads".
int ResolveNumThreads(int requested);

// Calls body(i) for every i in [0, num_items) on up to `num_threads` threads (<= 0: all cores).
// The first exception thrown by any body stops the hand-out of new items and is rethrown here after
// all threads have joined.
void ParallelFor(std::size_t num_items, int num_threads, const std::function<void(std::size_t)>& body);

// The same, also telling `body` which worker runs the item: 0 <= worker < ResolveNumThreads(num_threads).
// For scratch that outlives one item, one per worker (buffers reused from image to image).
void ParallelForOnWorkers(std::size_t num_items, int num_threads,
                          const std::function<void(std::size_t item, int worker)>& body);

}  // namespace lutex
