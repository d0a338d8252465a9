// RunQueue (run_queue.hpp): each thread takes its own run in order, then steals from the back
// of the others'; under contention every island is taken exactly once, and a thread that
// falls behind has its run finished by the others. parallelFor (parallel_for.hpp), built on
// it, calls f once per item, and the others take a stalled thread's items; collectInChunks gives
// the serial loop's items in the serial order at any thread count.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "parallel_for.hpp"
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

TEST(ParallelFor, EveryItemOnceAtAnySizeAndThreadCount) {
  for (const int threads : {1, 2, 3, 4})
    for (const int n : {0, 1, kParallelMin - 1, kParallelMin, 100, 1001, 5000}) {
      std::vector<std::atomic<int>> calls(n);
      for (auto& c : calls) c.store(0);
      parallelFor(n, threads, [&](int i) { calls[i].fetch_add(1); });
      int wrong = 0;
      for (int i = 0; i < n; ++i) wrong += calls[i].load() != 1;
      EXPECT_EQ(wrong, 0) << n << " items, " << threads << " threads";
    }
}

// Items kept by a loop (every third one, two entries for every fifth) come out as the serial
// loop gives them, split or not, at any size, chunk and thread count, into a vector that already
// holds some.
TEST(CollectInChunks, SerialOrderAtAnyThreadCount) {
  const auto keep = [](int begin, int end, std::vector<int>& out) {
    for (int i = begin; i < end; ++i) {
      if (i % 3 == 0) out.push_back(i);
      if (i % 5 == 0) out.push_back(-i);
    }
  };
  std::vector<std::vector<int>> scratch;
  for (const int threads : {1, 2, 4})
    for (const int n : {0, 1, 7, 100, 5000})
      for (const int chunk : {1, 3, 64, 10000})
        for (const bool split : {false, true}) {
          std::vector<int> serial = {42}, chunked = {42};
          keep(0, n, serial);
          collectInChunks(n, chunk, threads, split, scratch, chunked, keep);
          EXPECT_EQ(chunked, serial) << n << " items, chunk " << chunk << ", " << threads
                                     << " threads, split " << split;
        }
}

#ifdef _OPENMP
// Thread 1 stalls on its first item until an item three quarters of the way through its share
// is done: thread 0 finishes its own share and then takes thread 1's from the back (a static
// split would leave all of it to thread 1, and the wait would end after 1 s).
TEST(ParallelFor, AStalledThreadsItemsAreTakenByTheOther) {
  constexpr int kItems = 4000;
  std::vector<int> by(kItems, -1);
  std::atomic<bool> stalled{false};
  parallelFor(kItems, 2, [&](int i) {
    const int t = omp_get_thread_num();
    if (t == 1 && !stalled.exchange(true)) {
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(1);
      while (__atomic_load_n(&by[kItems / 2 + kItems / 8], __ATOMIC_RELAXED) < 0 &&
             std::chrono::steady_clock::now() < give_up)
        std::this_thread::yield();
    }
    __atomic_store_n(&by[i], t, __ATOMIC_RELAXED);
  });
  int second_half_by_0 = 0;
  for (int i = 0; i < kItems; ++i) {
    ASSERT_GE(by[i], 0) << i;
    if (i >= kItems / 2) second_half_by_0 += by[i] == 0;
  }
  EXPECT_GT(second_half_by_0, kItems / 4);
}
#endif

}  // namespace
}  // namespace ragdoll_sim
