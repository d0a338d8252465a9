// A loop of independent items over the step's threads.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "constants.hpp"
#include "run_queue.hpp"
#include "thread_team.hpp"

namespace ragdoll_sim {

// Whether n items go to `threads` threads: from kParallelMin items, and never for one thread. A
// region costs two handoffs between cores (about half a microsecond), more than a few items save.
inline bool splitOverThreads(int n, int threads) { return threads > 1 && n >= kParallelMin; }

// f(i) for i in [0, n) split over `threads` threads (more than one), whatever n. Each thread
// takes its share of the items (a contiguous part, as a static schedule gives it, so that it
// touches the same data step after step) in chunks from the front; one that is done takes chunks
// from the back of another's share (run_queue.hpp): the items' cost varies (a kept manifold
// against a new one) and so do the vCPUs' speeds, and a static split leaves one thread waiting
// at the end of the loop. f must be independent per item.
template <class F>
void parallelForSplit(int n, int threads, F&& f) {
  constexpr int kChunksPerThread = 16;
  const int chunk = std::max(1, n / (threads * kChunksPerThread));
  const int chunks = (n + chunk - 1) / chunk;
  // The caller's, kept between calls (the team reaches it through `queue`: in another thread
  // the thread_local name is that thread's own).
  thread_local RunQueue caller_queue;
  thread_local std::vector<int> runs;
  runs.resize(threads + 1);
  for (int t = 0; t <= threads; ++t) runs[t] = int(int64_t(chunks) * t / threads);
  RunQueue& queue = caller_queue;
  queue.reset(runs);
  const auto run = [&](int c) {
    const int end = std::min(n, (c + 1) * chunk);
    for (int i = c * chunk; i < end; ++i) f(i);
  };
  teamRun(threads, [&](int t) {
    for (int c; (c = queue.take(t)) >= 0;) run(c);
    for (int c; (c = queue.steal(t)) >= 0;) run(c);
  });
}

// f(i) for i in [0, n): split over the threads when splitOverThreads, else on the caller's thread
// without starting a region (parallelForSplit).
template <class F>
void parallelFor(int n, int threads, F&& f) {
  if (splitOverThreads(n, threads)) return parallelForSplit(n, threads, f);
  for (int i = 0; i < n; ++i) f(i);
}

// Items per chunk of collectInChunks for about 64 chunks, so that a thread done early has some
// to take.
inline int collectChunk(int n) { return std::max(1, (n + 63) / 64); }

// f(begin, end, out) over [0, n) in chunks of `chunk` items, each chunk into its own vector of
// `scratch` (kept between calls), then appended to `into` in chunk order: the same items in the
// same order as f(0, n, into), whatever the threads. Split over the threads when `split` (the
// caller weighs the loop's work against the cost of a parallel region).
template <class T, class F>
void collectInChunks(int n, int chunk, int threads, bool split,
                     std::vector<std::vector<T>>& scratch, std::vector<T>& into, F&& f) {
  const int chunks = (n + chunk - 1) / chunk;
  if (!split || threads < 2 || chunks < 2) return f(0, n, into);
  if (int(scratch.size()) < chunks) scratch.resize(chunks);
  parallelForSplit(chunks, threads, [&](int c) {
    scratch[c].clear();
    f(c * chunk, std::min(n, (c + 1) * chunk), scratch[c]);
  });
  for (int c = 0; c < chunks; ++c) into.insert(into.end(), scratch[c].begin(), scratch[c].end());
}

}  // namespace ragdoll_sim
