// rostest: ~sleep on the bundled ragdoll dropped from its spawn pose. With the defaults it comes
// to rest and sleeps within 10 s of sim time (~step's awake_bodies reaches 0), and stays asleep;
// with ~sleep/enabled false the same drop keeps every body awake to the end. Then the sleep
// settings changed at run time through dynamic_reconfigure (sleep_enabled, sleep_time,
// sleep_speed, rest_time, rest_substeps, rest_relax_iterations): the answers start from the
// nodes' parameters, off wakes every body and keeps it awake, on with a shorter time puts the
// resting ragdoll to sleep within that time, NaN is refused, and new thresholds and rest
// settings while asleep change in place (World::setSleep) without waking anything; ~step's
// resting_bodies shows the rest substeps taken after rest_time, off with rest_substeps 0 and
// back when they return.
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <map>

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

namespace {
// Steps in chunks of `chunk` until every body sleeps; the sim time it took, or -1 if none
// slept within `limit` s.
double timeToSleep(const SimClient& sim, int chunk, double limit) {
  const double t0 = sim.step(0).sim_time;
  for (double t = t0; t - t0 <= limit;) {
    const ragdoll_sim::Step::Response r = sim.step(chunk);
    if (!r.success) return -1.0;
    t = r.sim_time;
    if (r.awake_bodies == 0) return t - t0;
  }
  return -1.0;
}
}  // namespace

// Runs after the test above: /sleep_on's ragdoll is asleep, /sleep_off's at rest and awake.
TEST(Sleep, ReconfiguredAtRunTime) {
  const SimClient on("/sleep_on"), off("/sleep_off");
  std::map<std::string, double> now_on, now_off;
  ASSERT_TRUE(on.reconfigure({}, &now_on));
  ASSERT_TRUE(off.reconfigure({}, &now_off));
  // The answers start from each node's parameters, not the .cfg defaults.
  EXPECT_EQ(now_on["sleep_enabled"], 1.0);
  EXPECT_EQ(now_off["sleep_enabled"], 0.0) << "~sleep/enabled false from the launch file";
  EXPECT_DOUBLE_EQ(now_on["sleep_time"], 0.5);
  EXPECT_DOUBLE_EQ(now_on["sleep_speed"], 0.05);
  EXPECT_DOUBLE_EQ(now_on["rest_time"], 0.05);
  EXPECT_EQ(now_on["rest_substeps"], 2.0);
  EXPECT_EQ(now_on["rest_relax_iterations"], 1.0);
  EXPECT_EQ(now_off["rest_substeps"], 0.0) << "~sleep/rest_substeps 0 from the launch file";
  const uint32_t bodies = off.step(0).awake_bodies;
  ASSERT_GT(bodies, 1u);
  ASSERT_EQ(on.step(0).awake_bodies, 0u) << "the first test left /sleep_on asleep";

  // Off: every sleeping body wakes and stays awake.
  ASSERT_TRUE(on.reconfigure({{}, {}, {{"sleep_enabled", false}}}));
  for (int k = 0; k < 8; ++k) {
    const ragdoll_sim::Step::Response r = on.step(kChunk);
    ASSERT_TRUE(r.success);
    EXPECT_EQ(r.awake_bodies, bodies) << "asleep at " << r.sim_time << " s with sleep off";
  }
  // On again with a shorter sleep time: the resting ragdoll sleeps after about that time.
  ASSERT_TRUE(on.reconfigure({{{"sleep_time", 0.2}}, {}, {{"sleep_enabled", true}}}, &now_on));
  EXPECT_DOUBLE_EQ(now_on["sleep_time"], 0.2);
  const double slept_on = timeToSleep(on, 10, 2.0);
  EXPECT_GE(slept_on, 0.2 - 1e-6) << "asleep before sleep_time";
  EXPECT_LT(slept_on, 0.5) << "the default 0.5 s, not the new 0.2 s (-1: never within 2 s)";
  // /sleep_off's ragdoll, at rest and awake since the start, sleeps once sleep is on.
  ASSERT_TRUE(off.reconfigure({{}, {}, {{"sleep_enabled", true}}}));
  const double slept_off = timeToSleep(off, 10, 2.0);
  EXPECT_GE(slept_off, 0.5 - 1e-6);
  EXPECT_LT(slept_off, 1.0) << "-1: never within 2 s";

  // NaN is refused whole: the answer holds the values in force.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(on.reconfigure({{{"sleep_speed", nan}}, {}, {}}, &now_on));
  EXPECT_DOUBLE_EQ(now_on["sleep_speed"], 0.05);
  EXPECT_DOUBLE_EQ(now_on["sleep_time"], 0.2);
  EXPECT_EQ(on.step(kChunk).awake_bodies, 0u) << "a refused change must not rebuild or wake";
  // New thresholds while asleep: changed in place, nothing wakes (a rebuilt World would).
  ASSERT_TRUE(on.reconfigure({{{"sleep_time", 0.3}, {"sleep_speed", 0.04}}, {}, {}}, &now_on));
  EXPECT_DOUBLE_EQ(now_on["sleep_time"], 0.3);
  EXPECT_DOUBLE_EQ(now_on["sleep_speed"], 0.04);
  EXPECT_EQ(on.step(0).awake_bodies, 0u) << "new sleep thresholds woke the sleeping ragdoll";
  EXPECT_EQ(on.step(kChunk).awake_bodies, 0u);
  // The rest substeps' settings too (a NaN rest_time is refused whole).
  ASSERT_TRUE(on.reconfigure({{{"rest_time", nan}}, {{"rest_substeps", 0}}, {}}, &now_on));
  EXPECT_DOUBLE_EQ(now_on["rest_time"], 0.05);
  EXPECT_EQ(now_on["rest_substeps"], 2.0) << "refused whole";
  ASSERT_TRUE(on.reconfigure(
      {{{"rest_time", 0.1}}, {{"rest_substeps", 1}, {"rest_relax_iterations", 2}}, {}}, &now_on));
  EXPECT_DOUBLE_EQ(now_on["rest_time"], 0.1);
  EXPECT_EQ(now_on["rest_substeps"], 1.0);
  EXPECT_EQ(now_on["rest_relax_iterations"], 2.0);
  EXPECT_EQ(on.step(kChunk).awake_bodies, 0u) << "new rest settings woke the sleeping ragdoll";

  // Their effect, seen in ~step's resting_bodies: woken (sleep off, then on with a long sleep
  // time), the resting ragdoll takes the rest substeps after rest_time, leaves them at the next
  // step when rest_substeps goes to 0 and takes them again when they come back.
  ASSERT_TRUE(on.reconfigure({{{"sleep_time", 10.0}, {"rest_time", 0.05}},
                              {{"rest_substeps", 2}, {"rest_relax_iterations", 1}},
                              {{"sleep_enabled", false}}}));
  ASSERT_TRUE(on.reconfigure({{}, {}, {{"sleep_enabled", true}}}));
  const ragdoll_sim::Step::Response woken = on.step(1);
  EXPECT_EQ(woken.awake_bodies, bodies);
  EXPECT_EQ(woken.resting_bodies, 0u) << "resting before rest_time";
  const ragdoll_sim::Step::Response rested = on.step(200);
  EXPECT_EQ(rested.awake_bodies, bodies);
  EXPECT_EQ(rested.resting_bodies, bodies) << "the ragdoll at rest for 0.2 s is not resting";
  ASSERT_TRUE(on.reconfigure({{}, {{"rest_substeps", 0}}, {}}));
  const ragdoll_sim::Step::Response rest_off = on.step(1);
  EXPECT_EQ(rest_off.resting_bodies, 0u) << "rest_substeps 0 must turn them off";
  EXPECT_EQ(rest_off.awake_bodies, bodies);
  ASSERT_TRUE(on.reconfigure({{}, {{"rest_substeps", 2}}, {}}));
  EXPECT_EQ(on.step(1).resting_bodies, bodies) << "back on: the ragdoll has been slow long";
  std::printf("[ sleep    ] reconfigured: off kept %u bodies awake for 2 s; on with sleep_time "
              "0.2 s asleep after %.3f s; the other node on (0.5 s) after %.3f s\n", bodies,
              slept_on, slept_off);
}

int main(int argc, char** argv) {
  return runRosTests(argc, argv, "sleep_test", 1, [] {}, [] {});
}
