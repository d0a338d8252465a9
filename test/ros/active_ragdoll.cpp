// rostest: launch/active_ragdoll.launch (balance controller on). From sim time 0 the pelvis
// stays above 0.8 m for 5 s of sim time; then after an impulse of 20 N s forwards on the torso
// (at its centre of mass) it stays above 0.8 m for 5 more seconds and ends upright.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include <ragdoll_sim/ApplyImpulse.h>
#include <ragdoll_sim/Step.h>
#include <std_srvs/Empty.h>

#include "node_log.hpp"
#include "tf_snapshots.hpp"

using namespace ragdoll_test;

namespace {

const std::string kNode = "/ragdoll_sim";
std::vector<LinkMass> g_links;
std::string g_root;
std::unique_ptr<TfSnapshots> g_tf;

struct Span {
  double min_z = 1e9, max_tilt = 0.0, end_z = 0.0, end_tilt = 0.0;
  size_t samples = 0;
  double covered = 0.0;  // s of sim time between the first and the last sample
};

double tilt(const Snapshot& s, const std::string& link) {
  return std::acos(std::clamp(s.poses.at(link).linear().col(2).z(), -1.0, 1.0));
}

// Pelvis height and tilt over the snapshots with stamps in [from, from + length].
Span measure(const ros::Time& from, double length) {
  Span r;
  const std::vector<Snapshot> all = g_tf->range(from, from + ros::Duration(length));
  for (const Snapshot& s : all) {
    const double z = s.position(g_root).z();
    r.min_z = std::min(r.min_z, z);
    r.max_tilt = std::max(r.max_tilt, tilt(s, g_root));
    r.end_z = z;
    r.end_tilt = tilt(s, g_root);
  }
  r.samples = all.size();
  if (!all.empty()) r.covered = (all.back().stamp - all.front().stamp).toSec();
  return r;
}

}  // namespace

TEST(ActiveRagdoll, StandsFiveSecondsAndAfterA20NsShove) {
  ASSERT_GT(g_links.size(), 1u) << "robot_description missing or not a URDF";
  ros::NodeHandle nh;
  ros::Publisher impulse = nh.advertise<ragdoll_sim::ApplyImpulse>(kNode + "/apply_impulse", 10);
  ASSERT_TRUE(ros::service::waitForService(kNode + "/unpause", ros::Duration(30.0))) << "node did not come up";
  ASSERT_TRUE(waitConnected(impulse)) << "node does not subscribe ~apply_impulse";

  // Paused at start. Once /tf reaches us, one step (1 ms) publishes the spawn pose, the start
  // of what is measured.
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(20.0);
  while (ros::ok() && !g_tf->connected() && ros::WallTime::now() < deadline)
    ros::WallDuration(0.02).sleep();
  ASSERT_TRUE(g_tf->connected()) << "no /tf publisher";
  ros::WallDuration(0.2).sleep();
  ragdoll_sim::Step step;
  step.request.steps = 1;
  ASSERT_TRUE(ros::service::call(kNode + "/step", step));
  ASSERT_TRUE(step.response.success) << step.response.message;
  EXPECT_LT(step.response.sim_time, 0.01) << "the node did not start paused";
  const Snapshot start = g_tf->waitFor(ros::Time(), ros::WallTime(), 20.0);
  ASSERT_TRUE(start.valid()) << "no TF";
  EXPECT_NEAR(start.position(g_root).z(), 1.001, 2e-3) << "not spawned standing";
  std_srvs::Empty e;
  ASSERT_TRUE(ros::service::call(kNode + "/unpause", e));

  // 5 s of sim time standing.
  ASSERT_TRUE(g_tf->waitFor(start.stamp + ros::Duration(5.0), ros::WallTime(), 60.0).valid())
      << "sim time did not reach 5 s";
  const Span stand = measure(start.stamp, 5.0);
  EXPECT_GT(stand.samples, 100u);
  EXPECT_GT(stand.covered, 4.9);
  EXPECT_GT(stand.min_z, 0.8) << "pelvis fell below 0.8 m while standing";

  // The shove: 20 N s forwards at the torso's centre of mass.
  ragdoll_sim::ApplyImpulse cmd;
  cmd.link = "torso";
  cmd.frame = "link";
  cmd.point.z = 0.22;
  cmd.impulse.x = 20.0;
  const Snapshot before = g_tf->latest();
  impulse.publish(cmd);
  // The impulse acts within a step of arriving; measure from the last snapshot before sending.
  ASSERT_TRUE(g_tf->waitFor(before.stamp + ros::Duration(5.0), ros::WallTime(), 60.0).valid())
      << "sim time did not advance 5 s after the shove";
  const Span shove = measure(before.stamp, 5.0);
  // Did the shove land? The pelvis must have moved forwards.
  const Snapshot end = g_tf->latest();
  const double dx = end.position(g_root).x() - before.position(g_root).x();
  EXPECT_GT(shove.samples, 100u);
  EXPECT_GT(shove.min_z, 0.8) << "pelvis fell below 0.8 m after the shove";
  EXPECT_LT(shove.end_tilt, 0.2) << "not upright 5 s after the shove";
  std::printf("[ active   ] standing 5 s: pelvis min z %.3f m (%zu samples, max tilt %.3f rad); "
              "after 20 N s on the torso: min z %.3f m, max tilt %.3f rad, end z %.3f m, end tilt "
              "%.3f rad, pelvis moved %.3f m forwards\n",
              stand.min_z, stand.samples, stand.max_tilt, shove.min_z, shove.max_tilt, shove.end_z,
              shove.end_tilt, dx);
  RecordProperty("standing_min_z", std::to_string(stand.min_z));
  RecordProperty("shove_min_z", std::to_string(shove.min_z));
  RecordProperty("shove_max_tilt", std::to_string(shove.max_tilt));
  RecordProperty("shove_dx", std::to_string(dx));
}

int main(int argc, char** argv) {
  return runRosTests(
      argc, argv, "active_ragdoll_test", 2,
      [] {
        ros::NodeHandle nh;
        g_links = urdfLinks(&g_root);
        g_tf = std::make_unique<TfSnapshots>(nh, linkNames(g_links));
      },
      [] { g_tf.reset(); });
}
