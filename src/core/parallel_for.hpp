// A loop of independent items over the step's threads.
#pragma once

#include "constants.hpp"

namespace ragdoll_sim {

// Whether n items go to `threads` threads: from kParallelMin items, and never for one thread, since
// an OpenMP region costs microseconds even for a team of one: a good part of a small world's step.
inline bool splitOverThreads(int n, int threads) { return threads > 1 && n >= kParallelMin; }

// f(i) for i in [0, n): split over the threads when splitOverThreads, else on the caller's thread
// without entering OpenMP.
template <class F>
void parallelFor(int n, int threads, F&& f) {
  if (!splitOverThreads(n, threads)) {
    for (int i = 0; i < n; ++i) f(i);
    return;
  }
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int i = 0; i < n; ++i) f(i);
}

}  // namespace ragdoll_sim
