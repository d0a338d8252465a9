// rostest: ~sleep on the bundled ragdoll dropped from its spawn pose. With the defaults it comes
// to rest and sleeps within 10 s of sim time (~step's awake_bodies reaches 0), and stays asleep;
// with ~sleep/enabled false the same drop keeps every body awake to the end.
#include <gtest/gtest.h>

#include <cstdio>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {
constexpr int kChunk = 250;   // steps per ~step call (0.25 s at the default 1000 Hz)
constexpr int kChunks = 40;   // 10 s
}  // namespace

TEST(Sleep, DefaultSleepsAndDisabledStaysAwake) {
  const SimClient on("/sleep_on"), off("/sleep_off");
  ASSERT_TRUE(on.waitUp()) << "/sleep_on did not come up";
  ASSERT_TRUE(off.waitUp()) << "/sleep_off did not come up";
  const ragdoll_sim::Step::Response first_on = on.step(1), first_off = off.step(1);
  ASSERT_TRUE(first_on.success && first_off.success);
  const uint32_t bodies = first_on.awake_bodies;  // everything moves at the start of the drop
  ASSERT_GT(bodies, 1u);
  EXPECT_EQ(first_off.awake_bodies, bodies);
  double asleep_at = -1.0;  // s of sim time
  for (int k = 1; k <= kChunks; ++k) {
    const ragdoll_sim::Step::Response a = on.step(kChunk), b = off.step(kChunk);
    ASSERT_TRUE(a.success && b.success) << a.message << " / " << b.message;
    EXPECT_EQ(b.awake_bodies, bodies) << "~sleep/enabled false, yet asleep at " << b.sim_time << " s";
    if (asleep_at > 0.0) {
      EXPECT_EQ(a.awake_bodies, 0u) << "woke up by itself at " << a.sim_time << " s";
    }
    if (a.awake_bodies == 0 && asleep_at < 0.0) asleep_at = a.sim_time;
  }
  ASSERT_GT(asleep_at, 0.0) << "the default node's ragdoll never slept within 10 s";
  std::printf("[ sleep    ] %u bodies: asleep by %.2f s with the defaults; all awake at 10 s with "
              "~sleep/enabled false\n", bodies, asleep_at);
}

int main(int argc, char** argv) {
  return runRosTests(argc, argv, "sleep_test", 1, [] {}, [] {});
}
