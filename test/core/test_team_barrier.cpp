// TeamBarrier (team_barrier.hpp): no thread leaves a wait before the other has arrived, and
// every write before the barrier is seen after it, round after round with the same barrier.
#include <gtest/gtest.h>

#include <thread>

#include "team_barrier.hpp"

namespace ragdoll_sim {
namespace {

TEST(TeamBarrier, TwoThreadsSeeEachOthersWritesEveryRound) {
  constexpr int kRounds = 20000;
  TeamBarrier barrier;
  // Each round, thread t writes its slot, waits, reads the other's slot, waits again (so the
  // other cannot overwrite it before it was read). Plain ints: the barrier must order them.
  int slot[2] = {-1, -1};
  int mismatches[2] = {0, 0};
  const auto run = [&](int t) {
    for (int round = 0; round < kRounds; ++round) {
      slot[t] = round * 2 + t;
      barrier.wait(t, 2);
      if (slot[1 - t] != round * 2 + (1 - t)) ++mismatches[t];
      barrier.wait(t, 2);
    }
  };
  std::thread other(run, 1);
  run(0);
  other.join();
  EXPECT_EQ(mismatches[0], 0);
  EXPECT_EQ(mismatches[1], 0);
}

}  // namespace
}  // namespace ragdoll_sim
