// rostest: deleting a ragdoll, spawning one, and changing solver settings or friction at run time
// change the World in place. The launch-time ragdoll, asleep on the ground, stays asleep through
// all of them, which a rebuilt World (every body created awake) would not allow.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <string>

#include <ragdoll_sim/DeleteRagdoll.h>
#include <ragdoll_sim/SpawnRagdoll.h>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {
const std::string kNode = "/no_rebuild_sim";
constexpr int kChunk = 250;  // steps per ~step call

std::string urdfPath() { return std::string(RAGDOLL_SIM_SOURCE_DIR) + "/urdf/ragdoll.urdf"; }

bool spawn(const std::string& name, double x, std::string* message) {
  ragdoll_sim::SpawnRagdoll s;
  s.request.name = name;
  s.request.urdf_file = urdfPath();
  s.request.pose.position.x = x;
  s.request.pose.position.z = 1.2;
  s.request.pose.orientation.w = 1.0;
  if (!ros::service::call(kNode + "/spawn", s)) return false;
  *message = s.response.message;
  return s.response.success;
}

bool remove(const std::string& name, std::string* message) {
  ragdoll_sim::DeleteRagdoll d;
  d.request.name = name;
  if (!ros::service::call(kNode + "/delete", d)) return false;
  *message = d.response.message;
  return d.response.success;
}

// Steps until every body sleeps (at most `limit` s of sim time); false if they never do.
bool sleepAll(const SimClient& sim, double limit) {
  for (double t = 0.0; t <= limit; t += kChunk * 1e-3)
    if (sim.step(kChunk).awake_bodies == 0) return true;
  return false;
}
}  // namespace

TEST(NoRebuild, SleepersStayAsleep) {
  const SimClient sim(kNode);
  ASSERT_TRUE(sim.waitUp()) << kNode << " did not come up";
  const uint32_t n = sim.step(1).awake_bodies;  // the launch-time ragdoll's bodies, falling
  ASSERT_GT(n, 1u);
  std::string message;
  ASSERT_TRUE(spawn("second", 3.0, &message)) << message;
  ASSERT_TRUE(sleepAll(sim, 15.0)) << "the two ragdolls never slept";
  const uint32_t asleep = sim.step(1).awake_bodies;
  ASSERT_EQ(asleep, 0u);

  // Delete the second: the first stays asleep.
  ASSERT_TRUE(remove("second", &message)) << message;
  EXPECT_EQ(sim.step(1).awake_bodies, 0u) << "deleting a ragdoll woke the other one (rebuild?)";
  EXPECT_FALSE(sim.link("second", "pelvis").success) << "the deleted ragdoll is still there";
  EXPECT_TRUE(sim.link("", "pelvis").success);

  // Solver settings and friction at run time: nothing wakes.
  std::map<std::string, double> now;
  ASSERT_TRUE(sim.reconfigure({{}, {{"substeps", 4}, {"position_iterations", 2}}, {}}, &now));
  EXPECT_EQ(now["substeps"], 4.0);
  EXPECT_EQ(sim.step(1).awake_bodies, 0u) << "new solver settings woke the ragdoll (rebuild?)";
  ASSERT_TRUE(sim.reconfigure({{{"static_friction", 0.9}, {"kinetic_friction", 0.7}}, {}, {}}, &now));
  EXPECT_DOUBLE_EQ(now["static_friction"], 0.9);
  EXPECT_EQ(sim.step(1).awake_bodies, 0u) << "new friction woke the ragdoll (rebuild?)";
  ASSERT_TRUE(sim.reconfigure({{{"restitution", 0.2}}, {}, {}}, &now));
  EXPECT_EQ(sim.step(kChunk).awake_bodies, 0u) << "new restitution woke the ragdoll";

  // A new ragdoll far away falls while the first sleeps on.
  ASSERT_TRUE(spawn("third", -3.0, &message)) << message;
  const ragdoll_sim::Step::Response r = sim.step(10);
  EXPECT_EQ(r.awake_bodies, asleep + n) << "only the new ragdoll's bodies move";
  std::printf("[ rebuild  ] delete, substeps, friction, restitution: the sleeping ragdoll slept on; "
              "a spawn woke only its own %u bodies\n", r.awake_bodies);
}

int main(int argc, char** argv) {
  return runRosTests(argc, argv, "no_rebuild_test", 1, [] {}, [] {});
}
