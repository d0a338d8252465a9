// The runs of islands that the threads solve (World::Impl::partitionIslands), with stealing at the
// end. Thread t takes the islands of its own run from the front, in order: the same run step after
// step, so its bodies and constraints stay in its core's cache. A thread whose run is done takes
// the last island left in another run (from the back, the one its owner would reach last) instead
// of waiting at the end of the parallel region. The runs are cut by estimated work, which the
// threads' time does not follow (a vCPU slows, or an island costs more than its count of
// constraints says). Islands are independent (each writes only its own bodies, joints and contacts,
// in its fixed order), so which thread solves one does not change the result.
// parallelFor (parallel_for.hpp) hands out the chunks of a loop's items the same way.
//
// Each run is one 64-bit word, front in the low half and back in the high half, changed by
// compare-and-swap: the owner and a thief can never take the same island.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

namespace ragdoll_sim {

class RunQueue {
 public:
  // runs[t] .. runs[t + 1]: thread t's islands; runs.size() - 1 threads.
  void reset(const std::vector<int>& runs) {
    const int n = int(runs.size()) - 1;
    if (n > capacity_) {
      runs_.reset(new Run[n]);
      capacity_ = n;
    }
    count_ = n;
    for (int t = 0; t < n; ++t)
      runs_[t].state.store(pack(runs[t], runs[t + 1]), std::memory_order_relaxed);
  }
  // The next island of thread t's own run, or -1 when none is left.
  int take(int t) { return pop(runs_[t].state, true); }
  // An island from the back of another thread's run, or -1 when every run is done.
  int steal(int t) {
    for (int k = 1; k < count_; ++k)
      if (const int i = pop(runs_[(t + k) % count_].state, false); i >= 0) return i;
    return -1;
  }

 private:
  static uint64_t pack(int front, int back) {
    return uint64_t(uint32_t(back)) << 32 | uint32_t(front);
  }
  static int pop(std::atomic<uint64_t>& state, bool from_front) {
    uint64_t s = state.load(std::memory_order_relaxed);
    for (;;) {
      const int front = int(uint32_t(s)), back = int(s >> 32);
      if (front >= back) return -1;
      const uint64_t next = from_front ? pack(front + 1, back) : pack(front, back - 1);
      if (state.compare_exchange_weak(s, next, std::memory_order_relaxed))
        return from_front ? front : back - 1;
    }
  }
  struct alignas(64) Run {  // one cache line each: the owners take from their own at once
    std::atomic<uint64_t> state{0};
  };
  std::unique_ptr<Run[]> runs_;
  int capacity_ = 0, count_ = 0;
};

}  // namespace ragdoll_sim
