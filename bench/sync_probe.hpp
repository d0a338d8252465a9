// `bench_ragdoll sync`: what the solver's two-thread handoffs cost on this machine, for the
// record of a sitting (scripts/bench.sh runs it before every round). An empty region of two
// threads (teamRun, thread_team.hpp: parallelFor and the island solve open one per call) and a
// TeamBarrier wait (a split island's, team_barrier.hpp), each the median over batches. Both are
// cheap when the two cores share a cache and several times dearer when the threads talk across a
// slower link (on a VM, vCPUs placed on different core complexes), and the two-thread steps lose
// with them.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <vector>

#include "team_barrier.hpp"
#include "thread_team.hpp"

namespace ragdoll_sim {

struct SyncCost {
  double region_us = 0.0, barrier_us = 0.0;
};

inline SyncCost measureSync() {
  SyncCost cost;
  constexpr int kBatches = 7, kCalls = 20000;
  using Clock = std::chrono::steady_clock;
  const auto perCall = [](Clock::time_point t0) {
    return std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / kCalls;
  };
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  std::vector<double> regions, barriers;
  for (int b = 0; b < kBatches; ++b) {
    const Clock::time_point t0 = Clock::now();
    for (int i = 0; i < kCalls; ++i)  // a body the compiler keeps
      teamRun(2, [](int) { std::atomic_signal_fence(std::memory_order_seq_cst); });
    regions.push_back(perCall(t0));
    TeamBarrier barrier;
    Clock::time_point t1;
    teamRun(2, [&](int t) {
      barrier.wait(t, 2);
      if (t == 0) t1 = Clock::now();
      for (int i = 0; i < kCalls; ++i) barrier.wait(t, 2);
      if (t == 0) barriers.push_back(perCall(t1));
    });
  }
  cost.region_us = median(regions);
  cost.barrier_us = median(barriers);
  return cost;
}

}  // namespace ragdoll_sim
