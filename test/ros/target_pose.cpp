// rostest: joint targets on ~target_pose (sensor_msgs/JointState). A target for the left elbow
// (a hinge) and the left shoulder's y joint (a source joint of a ball chain) is reached within
// 0.05 rad, read back from /joint_states; commands naming an unknown joint or holding NaN are
// dropped with a warning and leave the pose alone. A target whose motion overflows on an
// unlimited axis (a spawned wheel's continuous joint) is dropped with a warning, the node goes
// on and takes the next target. Tests run in order and share one node.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>

#include <ragdoll_sim/SpawnRagdoll.h>
#include <sensor_msgs/JointState.h>

#include "node_log.hpp"

using namespace ragdoll_test;

namespace {

const std::string kNode = "/ragdoll_sim";

struct Fixture {
  ros::NodeHandle nh;
  ros::Subscriber states_sub, wheel_sub;
  ros::Publisher target_pub;
  std::unique_ptr<NodeWarnings> warnings;
  std::mutex mutex;
  sensor_msgs::JointState last, wheel;  // /joint_states, /wheel/joint_states

  void init() {
    states_sub = nh.subscribe("/joint_states", 50, &Fixture::onStates, this);
    wheel_sub = nh.subscribe<sensor_msgs::JointState>(
        "/wheel/joint_states", 50, [this](const sensor_msgs::JointState::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          wheel = *m;
        });
    target_pub = nh.advertise<sensor_msgs::JointState>(kNode + "/target_pose", 10);
    warnings = std::make_unique<NodeWarnings>(nh, kNode);
  }
  void onStates(const sensor_msgs::JointState::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    last = *m;
  }
  sensor_msgs::JointState latest() {
    std::lock_guard<std::mutex> lock(mutex);
    return last;
  }
  sensor_msgs::JointState latestWheel() {
    std::lock_guard<std::mutex> lock(mutex);
    return wheel;
  }
  // Position of `joint` in a joint_states message (NaN when absent).
  static double position(const sensor_msgs::JointState& s, const std::string& joint) {
    for (size_t i = 0; i < s.name.size() && i < s.position.size(); ++i)
      if (s.name[i] == joint) return s.position[i];
    return std::numeric_limits<double>::quiet_NaN();
  }
  // Waits (wall clock) for a joint_states message stamped at least `min_stamp`.
  sensor_msgs::JointState waitStamp(const ros::Time& min_stamp, double timeout = 20.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      sensor_msgs::JointState s = latest();
      if (!s.name.empty() && s.header.stamp >= min_stamp) return s;
      ros::WallDuration(0.01).sleep();
    }
    return sensor_msgs::JointState();
  }
};

Fixture* fx = nullptr;
const std::map<std::string, double> kTargets = {{"elbow_l", 1.2}, {"shoulder_l_y", -0.6}};
ros::Time g_reached;  // stamp at which both targets were reached

}  // namespace

TEST(TargetPose, A_ElbowAndShoulderReachTheirTargets) {
  ASSERT_TRUE(ros::service::waitForService(kNode + "/step", ros::Duration(30.0))) << "node did not come up";
  ASSERT_TRUE(waitConnected(fx->target_pub)) << "node does not subscribe ~target_pose";
  const sensor_msgs::JointState start = fx->waitStamp(ros::Time());
  ASSERT_FALSE(start.name.empty()) << "no /joint_states";
  for (const auto& [joint, target] : kTargets) {
    ASSERT_FALSE(std::isnan(Fixture::position(start, joint))) << joint << " not in joint_states";
    EXPECT_GT(std::abs(Fixture::position(start, joint) - target), 0.5) << joint << " starts at its target";
  }

  sensor_msgs::JointState cmd;
  for (const auto& [joint, target] : kTargets) {
    cmd.name.push_back(joint);
    cmd.position.push_back(target);
  }
  const ros::Time sent = fx->latest().header.stamp;
  fx->target_pub.publish(cmd);

  // Reached: every target within 0.05 rad, within 3 s of sim time.
  double err = 1e9;
  sensor_msgs::JointState s;
  for (ros::Time t = sent;;) {
    s = fx->waitStamp(t + ros::Duration(0.001));
    ASSERT_FALSE(s.name.empty()) << "joint_states stopped";
    err = 0.0;
    for (const auto& [joint, target] : kTargets)
      err = std::max(err, std::abs(Fixture::position(s, joint) - target));
    if (err < 0.05 || (s.header.stamp - sent).toSec() > 3.0) break;
    t = s.header.stamp;
  }
  EXPECT_LT(err, 0.05) << "targets not reached within 3 s of sim time: elbow_l "
                       << Fixture::position(s, "elbow_l") << ", shoulder_l_y "
                       << Fixture::position(s, "shoulder_l_y");
  g_reached = s.header.stamp;

  // ... and held.
  const sensor_msgs::JointState later = fx->waitStamp(s.header.stamp + ros::Duration(1.0));
  ASSERT_FALSE(later.name.empty());
  const double elbow = Fixture::position(later, "elbow_l"), shoulder = Fixture::position(later, "shoulder_l_y");
  EXPECT_NEAR(elbow, 1.2, 0.05);
  EXPECT_NEAR(shoulder, -0.6, 0.05);
  std::printf("[ target   ] reached within 0.05 rad after %.3f s sim; 1 s later elbow_l %.4f (target 1.2), "
              "shoulder_l_y %.4f (target -0.6)\n",
              (g_reached - sent).toSec(), elbow, shoulder);
  RecordProperty("time_to_reach", std::to_string((g_reached - sent).toSec()));
  RecordProperty("elbow_l", std::to_string(elbow));
  RecordProperty("shoulder_l_y", std::to_string(shoulder));
}

TEST(TargetPose, B_BadNamesAndNaNAreDropped) {
  sensor_msgs::JointState bad;
  bad.name = {"elbow_l", "no_such_joint"};
  bad.position = {0.2, 0.0};
  fx->target_pub.publish(bad);
  EXPECT_TRUE(fx->warnings->wait({"no_such_joint"}, 5.0)) << "no WARN naming the unknown joint";

  ros::WallDuration(1.2).sleep();  // same throttled call site
  sensor_msgs::JointState nan;
  nan.name = {"elbow_l"};
  nan.position = {std::numeric_limits<double>::quiet_NaN()};
  fx->target_pub.publish(nan);
  EXPECT_TRUE(fx->warnings->wait({"elbow_l", "not finite"}, 5.0)) << "no WARN about a NaN target";

  const sensor_msgs::JointState s = fx->waitStamp(fx->latest().header.stamp + ros::Duration(0.5));
  ASSERT_FALSE(s.name.empty());
  EXPECT_NEAR(Fixture::position(s, "elbow_l"), 1.2, 0.05) << "a dropped command moved the elbow";
}

// A hub and a wheel on a continuous joint (no limits: its target is not clamped to a range).
const char* kWheelUrdf = R"(<robot name="wheel">
  <link name="hub"><inertial><mass value="2"/><inertia ixx="0.02" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="rim"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.15"/><geometry><cylinder radius="0.2" length="0.05"/></geometry></collision></link>
  <joint name="spin" type="continuous"><parent link="hub"/><child link="rim"/><axis xyz="0 0 1"/></joint>
</robot>)";

TEST(TargetPose, C_OverflowingTargetIsDroppedAndTheNodeGoesOn) {
  ragdoll_sim::SpawnRagdoll spawn;
  spawn.request.name = "wheel";
  spawn.request.urdf = kWheelUrdf;
  spawn.request.pose.position.x = 3.0;  // away from the first ragdoll, gravity off
  spawn.request.pose.position.z = 5.0;
  ASSERT_TRUE(ros::service::call(kNode + "/spawn", spawn));
  ASSERT_TRUE(spawn.response.success) << spawn.response.message;
  // Finite inputs that pass the command checks: 1e308 rad moving at 1e308 rad/s passes the
  // largest double (1.8e308) after ~0.8 s of sim time, where the motor target is inf.
  sensor_msgs::JointState cmd;
  cmd.name = {"wheel/spin"};
  cmd.position = {1e308};
  cmd.velocity = {1e308};
  fx->target_pub.publish(cmd);
  EXPECT_TRUE(fx->warnings->wait({"'wheel'", "'spin'", "the target is dropped"}, 10.0))
      << "no WARN about the overflowing target";

  // The node goes on: both ragdolls publish finite joint states, and the wheel takes a new target.
  const ros::Time after = fx->latest().header.stamp + ros::Duration(0.3);
  const sensor_msgs::JointState first = fx->waitStamp(after);
  ASSERT_FALSE(first.name.empty()) << "joint_states stopped";
  EXPECT_NEAR(Fixture::position(first, "elbow_l"), 1.2, 0.05);
  cmd.position = {0.5};
  cmd.velocity.clear();
  fx->target_pub.publish(cmd);
  // Reached (the hinge angle is read in (-pi, pi]) and held for 1 s of sim time.
  const auto wheelAfter = [&](const ros::Time& stamp) {
    for (const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(20.0);
         ros::ok() && ros::WallTime::now() < deadline; ros::WallDuration(0.02).sleep()) {
      const sensor_msgs::JointState w = fx->latestWheel();
      if (w.header.stamp >= stamp) return w;
    }
    return sensor_msgs::JointState();
  };
  double spin = std::numeric_limits<double>::quiet_NaN();
  ros::Time reached;
  for (ros::Time t = after; reached.isZero();) {
    const sensor_msgs::JointState w = wheelAfter(t);
    ASSERT_FALSE(w.name.empty()) << "/wheel/joint_states stopped";
    spin = Fixture::position(w, "spin");
    ASSERT_TRUE(std::isfinite(spin)) << "spin " << spin;
    if (std::abs(spin - 0.5) < 0.05) reached = w.header.stamp;
    ASSERT_LT((w.header.stamp - after).toSec(), 10.0) << "the wheel did not take the new target: spin " << spin;
    t = w.header.stamp + ros::Duration(0.001);
  }
  const sensor_msgs::JointState held = wheelAfter(reached + ros::Duration(1.0));
  ASSERT_FALSE(held.name.empty());
  EXPECT_NEAR(Fixture::position(held, "spin"), 0.5, 0.05) << "the new target is not held";
  std::printf("[ target   ] overflowing target dropped with a WARN; the next one (0.5) reached after "
              "%.3f s sim, 1 s later spin %.4f\n",
              (reached - after).toSec(), Fixture::position(held, "spin"));
}

int main(int argc, char** argv) {
  return runFixtureTests(argc, argv, "target_pose_test", 2, fx);
}
