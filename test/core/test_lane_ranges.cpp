// The ranges of islands a thread solves together with lanes (extendsRange, island_solve.hpp):
// consecutive islands up to kLaneRangeWork, and, when other threads may steal and the threads
// keep a reserve, beyond kLaneRangeFill never more islands than the run still leaves after them;
// and when they keep it (StealReserve).
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

// The steps in [from, to) on which a StealReserve keeps the reserve, the first thread to end
// waiting `waited` of every region and stolen(k) islands stolen on step k if it kept it.
template <class Stolen>
int reservedSteps(int from, int to, double waited, Stolen&& stolen) {
  StealReserve s;
  int on = 0;
  for (int k = 0; k < to; ++k) {
    const bool reserved = s.on();
    if (k >= from) on += reserved;
    s.update(reserved, waited, reserved ? stolen(k) : 0);
  }
  return on;
}
int reservedSteps(int steps, double waited, int stolen) {
  return reservedSteps(0, steps, waited, [&](int) { return stolen; });
}

// Runs that end together never take the reserve; runs that end apart by more than an island
// (islands get stolen) keep it on nearly every step: windows of 64 steps, two steps apart.
TEST(StealReserve, KeptWhileItsIslandsAreStolen) {
  EXPECT_EQ(reservedSteps(4000, 0.0, 1), 0);
  EXPECT_EQ(reservedSteps(4000, 0.05, 1), 0);  // within a twelfth of the region
  EXPECT_GE(reservedSteps(4000, 0.5, 1), 3800);
}

// Runs that end apart by less than an island wait as long but leave nothing to steal: each
// window without steals holds off the next for 256, 512, 1024, 2048 steps, then 4096; a window
// that stole ends the pauses.
TEST(StealReserve, PausedWhileNothingIsStolen) {
  EXPECT_EQ(reservedSteps(4000, 0.5, 0), 4 * 64);
  EXPECT_EQ(reservedSteps(20000, 0.5, 0), 8 * 64);
  const auto from_2000 = [](int k) { return k > 2000 ? 1 : 0; };  // the window at 1992 steals
  EXPECT_GE(reservedSteps(2100, 4000, 0.5, from_2000), 1800);
}

}  // namespace
}  // namespace ragdoll_sim
