// Unit tests of the wall-clock pacing at a real-time factor (src/scene/pacing.*), on made-up
// time points (no real clock).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "pacing.hpp"

using namespace ragdoll_sim::scene;
using Clock = Pacer::Clock;
using std::chrono::milliseconds;

namespace {

// Steps taken when the loop wakes every `tick` over `span` of wall time.
int64_t stepsOver(Pacer& p, Clock::time_point start, milliseconds span, milliseconds tick) {
  int64_t n = 0;
  for (Clock::time_point t = start; t <= start + span; t += tick) n += p.take(t);
  return n;
}

}  // namespace

TEST(Pacer, RealTimeFactorScalesTheStepRate) {
  const Clock::time_point t0{};
  for (double rtf : {1.0, 0.1, 0.5, 2.0, 5.0}) {
    Pacer p;
    p.configure(1000000, rtf, 1000);  // 1 ms steps
    p.restart(t0);
    // One wall second: 1000 * rtf steps (plus the one due at t0).
    const int64_t n = stepsOver(p, t0, milliseconds(1000), milliseconds(1));
    EXPECT_EQ(n, static_cast<int64_t>(1000 * rtf) + 1) << "rtf " << rtf;
    EXPECT_EQ(p.droppedSteps(), 0);
  }
}

TEST(Pacer, NextStepTime) {
  Pacer p;
  p.configure(1000000, 0.5, 100);
  const Clock::time_point t0{};
  p.restart(t0);
  EXPECT_EQ(p.take(t0), 1);
  EXPECT_EQ(p.next(t0), t0 + milliseconds(2)) << "1 ms of sim time takes 2 ms at 0.5x";
  EXPECT_EQ(p.take(t0 + milliseconds(1)), 0);
  EXPECT_EQ(p.take(t0 + milliseconds(2)), 1);
}

TEST(Pacer, AsFastAsPossible) {
  for (double rtf : {0.0, std::numeric_limits<double>::infinity()}) {
    Pacer p;
    p.configure(1000000, rtf, 50);
    p.restart(Clock::time_point{});
    EXPECT_TRUE(p.asFastAsPossible());
    EXPECT_EQ(p.take(Clock::time_point{}), 50);
    EXPECT_EQ(p.next(Clock::time_point{} + milliseconds(3)), Clock::time_point{} + milliseconds(3));
  }
}

TEST(Pacer, DropsABacklogInsteadOfSpiralling) {
  Pacer p;
  p.configure(1000000, 1.0, 100);  // at most 100 steps per call
  const Clock::time_point t0{};
  p.restart(t0);
  // One second late: 100 steps now, the remaining ~900 are dropped.
  EXPECT_EQ(p.take(t0 + milliseconds(1000)), 100);
  EXPECT_GT(p.droppedSteps(), 850);
  // Back on schedule afterwards: one step per millisecond.
  const Clock::time_point t1 = t0 + milliseconds(1000);
  EXPECT_LE(p.take(t1 + milliseconds(1)), 2);
  EXPECT_LE(p.take(t1 + milliseconds(2)), 1);
}

TEST(Pacer, RealTimeFactorValidation) {
  EXPECT_STREQ(realTimeFactorError(1.0), "");
  EXPECT_STREQ(realTimeFactorError(0.0), "");
  EXPECT_STREQ(realTimeFactorError(std::numeric_limits<double>::infinity()), "");
  EXPECT_STRNE(realTimeFactorError(-1.0), "");
  EXPECT_STRNE(realTimeFactorError(0.001), "");
  EXPECT_STRNE(realTimeFactorError(std::nan("")), "");
}
