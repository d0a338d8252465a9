// A barrier for the two threads that solve a split island (island_split.hpp), in place of
// `#pragma omp barrier`, which is several times slower per wait where a split island waits twice
// per boundary sweep and around its prepares and restitution. A counter and a flag, each on its own
// cache line: the last thread to arrive resets the counter and flips the flag, the others spin on
// the flag (sense reversal, so the same barrier serves the next wait at once). Release on arrival
// and acquire on leaving order every write before the wait before every read after it, as the
// OpenMP barrier's implied flush does. A waiter that spins long (its partner was preempted) yields
// its core. Timed (setTimed), each thread sums its waits (StepProfile::solve_wait).
#pragma once

#include <atomic>
#include <cassert>
#include <chrono>
#include <thread>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace ragdoll_sim {

class TeamBarrier {
 public:
  static constexpr int kMaxTeam = 2;  // a split island has two halves

  // Thread `slot` (0 .. team - 1) of a team of `team` <= kMaxTeam threads waits for the others.
  void wait(int slot, int team) {
    assert(team <= kMaxTeam && slot >= 0 && slot < team);
    if (team <= 1) return;
    const int sense = local_[slot].sense ^= 1;
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) == team - 1) {
      arrived_.store(0, std::memory_order_relaxed);
      sense_.store(sense, std::memory_order_release);
      return;
    }
    const Clock::time_point start = timed_ ? Clock::now() : Clock::time_point();
    for (int spins = 0; sense_.load(std::memory_order_acquire) != sense; ++spins) {
      if (spins < kSpins) pause();
      else std::this_thread::yield();
    }
    if (timed_) {
      const std::chrono::duration<double, std::micro> waited = Clock::now() - start;
      local_[slot].waited += waited.count();
    }
  }
  // Set between the team's waits (outside its region).
  void setTimed(bool on) { timed_ = on; }
  // The waits of every thread since the last call, in microseconds; set back to 0 (outside the
  // team's region).
  double takeWaited() {
    double sum = 0.0;
    for (Local& l : local_) {
      sum += l.waited;
      l.waited = 0.0;
    }
    return sum;
  }

 private:
  static constexpr int kSpins = 1 << 16;
  static void pause() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#endif
  }
  using Clock = std::chrono::steady_clock;
  struct alignas(64) Local {
    int sense = 0;
    double waited = 0.0;  // microseconds, while timed
  };
  bool timed_ = false;
  alignas(64) std::atomic<int> arrived_{0};
  alignas(64) std::atomic<int> sense_{0};
  Local local_[kMaxTeam];  // each thread's sense, on its own line
};

}  // namespace ragdoll_sim
