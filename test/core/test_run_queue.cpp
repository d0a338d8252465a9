// RunQueue (run_queue.hpp): each thread takes its own run in order, then steals from the back
// of the others'; under contention every island is taken exactly once, and a thread that
// falls behind has its run finished by the others.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "run_queue.hpp"

namespace ragdoll_sim {
namespace {

TEST(RunQueue, OwnRunInOrderThenTheOthersFromTheBack) {
  RunQueue q;
  q.reset({0, 3, 5, 9});  // runs [0, 3), [3, 5), [5, 9)
  EXPECT_EQ(q.take(1), 3);
  EXPECT_EQ(q.take(1), 4);
  EXPECT_EQ(q.take(1), -1);
  // thread 1 steals from thread 2's run first (the next thread), from its back
  EXPECT_EQ(q.steal(1), 8);
  EXPECT_EQ(q.steal(1), 7);
  EXPECT_EQ(q.take(2), 5);  // the owner still goes from the front
  EXPECT_EQ(q.steal(1), 6);
  EXPECT_EQ(q.take(2), -1);
  EXPECT_EQ(q.steal(2), 2);  // thread 2 wraps round to thread 0's run
  EXPECT_EQ(q.take(0), 0);
  EXPECT_EQ(q.take(0), 1);
  EXPECT_EQ(q.take(0), -1);
  for (int t = 0; t < 3; ++t) EXPECT_EQ(q.steal(t), -1);
  // reset serves the next step, with fewer threads and empty runs too
  q.reset({0, 0, 2});
  EXPECT_EQ(q.take(0), -1);
  EXPECT_EQ(q.steal(0), 1);
  EXPECT_EQ(q.take(1), 0);
  EXPECT_EQ(q.take(1), -1);
  EXPECT_EQ(q.steal(1), -1);
}

// Threads of unequal runs (one short, one long, one empty), the long run's owner starting late
// (once the others have stolen from its run, or after 1 s without): each island is taken once,
// and the others have taken part of the late thread's run.
TEST(RunQueue, EveryIslandOnceUnderContentionAndALateThreadIsHelped) {
  constexpr int kThreads = 3, kIslands = 20000, kRounds = 20;
  const std::vector<int> runs = {0, 10, kIslands, kIslands};
  RunQueue q;
  std::vector<std::atomic<int>> taken(kIslands);
  for (int round = 0; round < kRounds; ++round) {
    for (auto& c : taken) c.store(0);
    q.reset(runs);
    std::atomic<int> from_late_run{0};  // islands of run 1 taken by threads 0 and 2
    const auto work = [&](int t) {
      if (t == 1) {  // starts once another thread has stolen from its run (or after 1 s)
        const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(1);
        while (from_late_run.load() == 0 && std::chrono::steady_clock::now() < give_up)
          std::this_thread::yield();
      }
      for (int k; (k = q.take(t)) >= 0;) taken[k].fetch_add(1);
      for (int k; (k = q.steal(t)) >= 0;) {
        taken[k].fetch_add(1);
        if (k >= runs[1] && k < runs[2]) from_late_run.fetch_add(1);
      }
    };
    std::vector<std::thread> others;
    for (int t = 1; t < kThreads; ++t) others.emplace_back(work, t);
    work(0);
    for (auto& th : others) th.join();
    int wrong = 0;
    for (int k = 0; k < kIslands; ++k) wrong += taken[k].load() != 1;
    EXPECT_EQ(wrong, 0) << "round " << round;
    EXPECT_GT(from_late_run.load(), 0) << "round " << round;
  }
}

}  // namespace
}  // namespace ragdoll_sim
