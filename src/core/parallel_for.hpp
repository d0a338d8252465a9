// A loop of independent items over the step's threads.
#pragma once

#include "constants.hpp"

namespace ragdoll_sim {

// f(i) for i in [0, n): split over `threads` threads from kParallelMin items; below that, or with
// one thread, on the caller's thread without entering OpenMP, whose region costs microseconds even
// for a team of one: a good part of a small world's whole step.
template <class F>
void parallelFor(int n, int threads, F&& f) {
  if (threads <= 1 || n < kParallelMin) {
    for (int i = 0; i < n; ++i) f(i);
    return;
  }
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int i = 0; i < n; ++i) f(i);
}

}  // namespace ragdoll_sim
