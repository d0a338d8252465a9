// teamRun (thread_team.hpp): every thread of a region runs once with its slot, the caller returns
// only when all are done and sees their writes, and the team survives what a World meets: regions
// of other sizes, nesting, idle gaps long enough to sleep, several calling threads, and a fork.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "thread_team.hpp"

namespace ragdoll_sim {
namespace {

// One region of n threads: each writes its slot into its own entry (plain ints: the region's end
// must order them before the caller's reads); false on any wrong slot or missing thread.
bool regionRunsEveryThreadOnce(int n) {
  std::vector<int> seen(size_t(n), 0), size(size_t(n), 0);
  std::atomic<int> wrong{0};
  teamRun(n, [&](int t) {
    const std::pair<int, int> slot = teamSlot();
    if (slot.first != t || t < 0 || t >= n) {
      wrong.fetch_add(1);
      return;
    }
    ++seen[size_t(t)];
    size[size_t(t)] = slot.second;
  });
  for (int t = 0; t < n; ++t)
    if (seen[size_t(t)] != 1 || size[size_t(t)] != n) return false;
  return wrong.load() == 0 && teamSlot() == std::make_pair(0, 1);
}

TEST(ThreadTeam, EveryThreadRunsOnceWithItsSlotRegionAfterRegion) {
  EXPECT_EQ(teamSlot(), std::make_pair(0, 1));
  int failed = 0;
  for (int round = 0; round < 5000; ++round) failed += !regionRunsEveryThreadOnce(2);
  EXPECT_EQ(failed, 0);
}

TEST(ThreadTeam, RegionsOfOtherSizesGrowAndReuseTheTeam) {
  for (const int n : {1, 2, 4, 3, 8, 2, 1, 5})
    EXPECT_TRUE(regionRunsEveryThreadOnce(n)) << n << " threads";
}

TEST(ThreadTeam, ARegionInsideARegionRunsOnItsThreadAlone) {
  std::atomic<int> inner_calls{0}, wrong{0};
  teamRun(2, [&](int t) {
    teamRun(4, [&](int u) {
      inner_calls.fetch_add(1);
      if (u != 0 || teamSlot() != std::make_pair(0, 1)) wrong.fetch_add(1);
    });
    if (teamSlot() != std::make_pair(t, 2)) wrong.fetch_add(1);  // the outer slot is back
  });
  EXPECT_EQ(inner_calls.load(), 2);
  EXPECT_EQ(wrong.load(), 0);
}

TEST(ThreadTeam, ASleepingWorkerWakesForTheNextRegion) {
  // Longer than a worker spins (kSpinTime, 1 ms): each region finds the worker asleep.
  for (int round = 0; round < 5; ++round) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    EXPECT_TRUE(regionRunsEveryThreadOnce(2)) << "round " << round;
  }
}

TEST(ThreadTeam, CallersOnSeveralThreadsEachHaveTheirOwnTeam) {
  std::atomic<int> failed{0};
  const auto caller = [&] {
    for (int round = 0; round < 2000; ++round) failed += !regionRunsEveryThreadOnce(3);
  };
  std::thread a(caller), b(caller);
  caller();
  a.join();
  b.join();
  EXPECT_EQ(failed.load(), 0);
}

TEST(ThreadTeam, AForkedChildRunsRegionsWithoutItsParentsThreads) {
  ASSERT_TRUE(regionRunsEveryThreadOnce(2));  // this thread's team has a worker now
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    alarm(10);  // a region waiting for the parent's worker would hang: SIGALRM ends it
    _exit(regionRunsEveryThreadOnce(2) && regionRunsEveryThreadOnce(3) ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_TRUE(regionRunsEveryThreadOnce(2));
}

}  // namespace
}  // namespace ragdoll_sim
