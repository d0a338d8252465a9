// `bench_ragdoll sync`: what the solver's two-thread handoffs cost on this machine and how fast
// its two cores run at once, for the record of a sitting (scripts/bench.sh runs it before every
// round). An empty region of two threads (teamRun, thread_team.hpp: parallelFor and the island
// solve open one per call) and a TeamBarrier wait (a split island's, team_barrier.hpp), each the
// median over batches. Both are cheap when the two cores share a cache and several times dearer
// when the threads talk across a slower link (on a VM, vCPUs placed on different core
// complexes), and the two-thread steps lose with them. The cores' speed: the same world steps
// on one thread alone, then on two threads at once, each its own world; the ceiling is the work
// both do at once over the work one does alone (2 when neither slows the other, less where both
// busy run slower), what two threads can gain that round on work that fits a core's cache.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "team_barrier.hpp"
#include "thread_team.hpp"

namespace ragdoll_sim {

struct SyncCost {
  double region_us = 0.0, barrier_us = 0.0;
  // each thread's speed with both busy, as a fraction of one thread's alone (the mean of
  // the two alone); their sum
  double core_speed[2] = {0.0, 0.0};
  double ceiling = 0.0;
};

// step(t, k): thread t (0 the caller, 1 another) steps its own world k steps on one thread.
template <class Step>
SyncCost measureSync(Step&& step) {
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
  // Each thread alone while the other waits, then both at once, in turns, so that a change of
  // the host's load falls on all three; the worlds first settle into the cost of their rest.
  constexpr int kSettleSteps = 2000, kSteps = 100;
  std::vector<double> alone[2], pair[2];
  TeamBarrier barrier;
  const auto timed = [&](int t) {
    const Clock::time_point t0 = Clock::now();
    step(t, kSteps);
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };
  // Plain threads, not a team region: a world's step inside a region would take the region's
  // thread number for its own (teamSlot).
  const auto run = [&](int t) {
    step(t, kSettleSteps);
    for (int b = 0; b < kBatches; ++b) {
      for (int who = 0; who < 2; ++who) {
        barrier.wait(t, 2);
        if (t == who) alone[t].push_back(timed(t));
      }
      barrier.wait(t, 2);
      pair[t].push_back(timed(t));
    }
  };
  std::thread other(run, 1);
  run(0);
  other.join();
  // against the mean speed alone: a one-thread run takes either core
  const double one = 0.5 / median(alone[0]) + 0.5 / median(alone[1]);
  for (int t = 0; t < 2; ++t) cost.core_speed[t] = 1.0 / median(pair[t]) / one;
  cost.ceiling = cost.core_speed[0] + cost.core_speed[1];
  return cost;
}

}  // namespace ragdoll_sim
