// The ranges of islands a thread solves together with lanes (extendsRange, island_solve.hpp):
// consecutive islands up to kLaneRangeWork, and, when other threads may steal and the threads
// keep a reserve, beyond kLaneRangeFill never more islands than the run still leaves after them;
// and when they keep it (StealReserve: the faster of the two, timed).
#include <gtest/gtest.h>

#include <vector>

#include "island_solve.hpp"

namespace ragdoll_sim {
namespace {

// Islands of `work` bodies each, back to back in the body array.
std::vector<IslandRange> islands(int count, int work) {
  std::vector<IslandRange> r(count);
  for (int k = 0; k < count; ++k) {
    r[k].body_begin = k * work;
    r[k].body_end = (k + 1) * work;
  }
  return r;
}

// The sizes of the ranges that solveIslands' loop cuts a run [0, n) into; shared: other
// threads may steal from its back; fill: kLaneRangeFill with the reserve, else kLaneRangeWork.
std::vector<int> rangeSizes(const std::vector<IslandRange>& rs, bool shared,
                            int fill = kLaneRangeFill) {
  std::vector<int> sizes;
  const int n = int(rs.size());
  IslandRange c;
  bool open = false;
  for (int k = 0; k < n; ++k) {
    if (open && extendsRange(c, rs[k], k, shared ? n - k - 1 : n, fill)) continue;
    if (open) sizes.push_back(c.island_end - c.island_begin);
    c = rs[k];
    c.island_begin = k;
    c.island_end = k + 1;
    open = true;
  }
  if (open) sizes.push_back(c.island_end - c.island_begin);
  return sizes;
}

TEST(LaneRanges, AloneTheRangesFillUpToTheWork) {
  const int per = kLaneRangeWork / 8;  // 8 islands per full range
  EXPECT_EQ(rangeSizes(islands(20, per), false), (std::vector<int>{8, 8, 4}));
}

// Shared, a thread holds at most half of what is left: the other thread, done with its own
// run, still finds islands to steal at the end instead of waiting for a whole range.
TEST(LaneRanges, SharedTheRangesShrinkTowardsTheEndOfTheRun) {
  const int per = kLaneRangeWork / 8;
  EXPECT_EQ(rangeSizes(islands(40, per), true), (std::vector<int>{8, 8, 8, 8, 4, 2, 2}));
  const int half_fill = kLaneRangeFill / 2;  // a ragdoll of ragdoll15 with its contacts
  EXPECT_EQ(rangeSizes(islands(10, half_fill), true), (std::vector<int>{5, 2, 2, 1}));
}

// Without the reserve (a step after runs that ended together) they fill up to the work.
TEST(LaneRanges, SharedWithoutTheReserveTheRangesFillUpToTheWork) {
  const int half_fill = kLaneRangeFill / 2;
  EXPECT_EQ(rangeSizes(islands(10, half_fill), true, kLaneRangeWork), (std::vector<int>{6, 4}));
}

// ... but not below kLaneRangeFill: one island alone would fill the lanes by half.
TEST(LaneRanges, SharedTheRangesKeepTheFill) {
  const int small = 4;  // 16 of them are within kLaneRangeFill: one range
  EXPECT_EQ(rangeSizes(islands(16, small), true), (std::vector<int>{16}));
  const int third = kLaneRangeFill / 3;
  EXPECT_EQ(rangeSizes(islands(6, third), true), (std::vector<int>{3, 3}));
}

TEST(LaneRanges, OnlyConsecutiveIslandsWithTheSameSubsteps) {
  std::vector<IslandRange> rs = islands(4, 4);
  rs[2].resting = true;  // rest substeps: not with the full ones
  EXPECT_EQ(rangeSizes(rs, false), (std::vector<int>{2, 1, 1}));
  rs = islands(4, 4);
  rs[2].body_begin += 1;  // a gap in the bodies (an island solved elsewhere)
  rs[2].body_end += 1;
  rs[3].body_begin += 1;
  rs[3].body_end += 1;
  EXPECT_EQ(rangeSizes(rs, false), (std::vector<int>{2, 2}));
}

// The steps in [from, to) on which a StealReserve keeps the reserve, step k's parallel region
// taking seconds(k, reserved).
template <class Seconds>
int reservedSteps(int from, int to, Seconds&& seconds) {
  StealReserve s;
  int on = 0;
  for (int k = 0; k < to; ++k) {
    const bool reserved = s.on();
    if (k >= from) on += reserved;
    s.update(seconds(k, reserved));
  }
  return on;
}
// A region of 100 us, `factor` times that with the reserve.
int reservedSteps(int steps, double factor) {
  return reservedSteps(0, steps, [&](int, bool r) { return r ? 100e-6 * factor : 100e-6; });
}

// Every 512 steps it tries 32 steps without the reserve and 32 with it, then keeps the faster:
// over 4096 steps the reserve is on in the 8 trials with it (256 steps) and, where it is the
// faster, also in the 8 x 448 steps after them.
TEST(StealReserve, KeptWhereItTimesFaster) {
  EXPECT_EQ(reservedSteps(4096, 0.95), 8 * (32 + 448));
  EXPECT_EQ(reservedSteps(4096, 1.05), 8 * 32);
  EXPECT_EQ(reservedSteps(4096, 1.0), 8 * 32);  // a tie keeps the lanes' fill
}

// The first steps of each trial (the caches follow the new ranges) are not timed, and a change
// in which is faster is followed from the next period on.
TEST(StealReserve, IgnoresEachTrialsFirstStepsAndFollowsAChange) {
  // The reserve is 5 % faster once settled; its trial's slow first step, timed, would decide
  // against it.
  const auto settling = [](int k, bool r) {
    return r ? (k % 512 == 32 ? 1e-3 : 95e-6) : 100e-6;
  };
  EXPECT_EQ(reservedSteps(0, 1024, settling), 2 * (32 + 448));
  // The reserve is faster up to step 1024, slower from then on.
  const auto turning = [](int k, bool r) { return r ? (k < 1024 ? 90e-6 : 110e-6) : 100e-6; };
  EXPECT_EQ(reservedSteps(0, 1024, turning), 2 * (32 + 448));
  EXPECT_EQ(reservedSteps(1024, 2048, turning), 2 * 32);
}

}  // namespace
}  // namespace ragdoll_sim
