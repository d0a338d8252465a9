// Unit tests of the per-kind warning throttle (src/scene/warn_throttle.*).
#include <gtest/gtest.h>

#include "warn_throttle.hpp"

using namespace ragdoll_sim::scene;

TEST(WarnThrottle, EachKindOncePerPeriodWithTheHeldBackCount) {
  WarnThrottle t(1.0);
  uint64_t held = 99;
  EXPECT_TRUE(t.allow("impulse/unknown link", 10.0, &held));
  EXPECT_EQ(held, 0u);
  // A flood of one kind is held back ...
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(t.allow("impulse/unknown link", 10.1 + 0.1 * i, &held));
  // ... but another kind still goes out at once.
  EXPECT_TRUE(t.allow("impulse/not finite", 10.2, &held));
  EXPECT_EQ(held, 0u);
  // After the period the first kind goes out again and tells how many it held back.
  EXPECT_TRUE(t.allow("impulse/unknown link", 11.0, &held));
  EXPECT_EQ(held, 5u);
  EXPECT_FALSE(t.allow("impulse/unknown link", 11.5, &held));
  EXPECT_TRUE(t.allow("impulse/unknown link", 12.5, &held));
  EXPECT_EQ(held, 1u);
}
