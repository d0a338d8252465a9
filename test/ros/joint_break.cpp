// rostest: a joint with a low break_force (the left wrist, 50 N, from ~joints) breaks under an
// impulse on the hand: one ragdoll_sim/JointBroken naming it arrives on ~joint_broken, and the
// hand then flies away from the forearm (distance from the hand's origin to the wrist anchor on
// the forearm, from TF): 5 N s on the 0.45 kg hand is ~11 m/s once the wrist has let go.
// ~reset then rejoins it.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <mutex>

#include <ragdoll_sim/ApplyImpulse.h>
#include <ragdoll_sim/JointBroken.h>
#include <std_srvs/Empty.h>

#include "node_log.hpp"
#include "tf_snapshots.hpp"

using namespace ragdoll_test;

namespace {

const std::string kNode = "/ragdoll_sim";
constexpr double kBreakForce = 50.0;  // joint_break.test

std::vector<LinkMass> g_links;
std::unique_ptr<TfSnapshots> g_tf;
std::mutex g_mutex;
std::vector<ragdoll_sim::JointBroken> g_broken;

void onBroken(const ragdoll_sim::JointBroken::ConstPtr& m) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_broken.push_back(*m);
}

size_t brokenCount() {
  std::lock_guard<std::mutex> lock(g_mutex);
  return g_broken.size();
}

// The wrist anchor in the forearm frame: the URDF origin of joint wrist_l.
Eigen::Isometry3d wristOrigin() {
  std::string xml;
  ros::param::get("/robot_description", xml);
  urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (!model || !model->getJoint("wrist_l")) return T;
  const urdf::Pose& o = model->getJoint("wrist_l")->parent_to_joint_origin_transform;
  T.translation() = Vec3(o.position.x, o.position.y, o.position.z);
  return T;
}

// Distance from the hand origin to the wrist anchor carried by the forearm.
double gap(const Snapshot& s, const Eigen::Isometry3d& wrist) {
  return (s.poses.at("hand_l").translation() - (s.poses.at("lower_arm_l") * wrist).translation()).norm();
}

}  // namespace

TEST(JointBreak, WeakWristBreaksAndTheHandFliesOff) {
  ASSERT_GT(g_links.size(), 1u) << "robot_description missing or not a URDF";
  ros::NodeHandle nh;
  ros::Subscriber sub = nh.subscribe(kNode + "/joint_broken", 10, onBroken);
  ros::Publisher impulse = nh.advertise<ragdoll_sim::ApplyImpulse>(kNode + "/apply_impulse", 10);
  ASSERT_TRUE(ros::service::waitForService(kNode + "/step", ros::Duration(30.0))) << "node did not come up";
  ASSERT_TRUE(waitConnected(sub)) << "node does not publish ~joint_broken";
  ASSERT_TRUE(waitConnected(impulse)) << "node does not subscribe ~apply_impulse";
  const Eigen::Isometry3d wrist = wristOrigin();
  ASSERT_GT(wrist.translation().norm(), 0.1) << "URDF has no joint wrist_l";

  Snapshot before = g_tf->next(20.0);
  ASSERT_TRUE(before.valid()) << "no TF";
  EXPECT_LT(gap(before, wrist), 0.005) << "hand not on the wrist before the impulse";
  EXPECT_EQ(brokenCount(), 0u) << "a joint broke before the impulse";

  // 5 N s pulling the hand down along the forearm (hand frame: z up the arm at rest): the wrist
  // has to stop about 4 N s of it within a substep, far above 50 N.
  ragdoll_sim::ApplyImpulse cmd;
  cmd.link = "hand_l";
  cmd.frame = "link";
  cmd.point.z = -0.09;
  cmd.impulse.z = -5.0;
  impulse.publish(cmd);

  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(10.0);
  while (ros::ok() && brokenCount() == 0 && ros::WallTime::now() < deadline)
    ros::WallDuration(0.01).sleep();
  ASSERT_EQ(brokenCount(), 1u) << "no JointBroken on " << kNode << "/joint_broken within 10 s";
  ragdoll_sim::JointBroken m;
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    m = g_broken[0];
  }
  EXPECT_EQ(m.joint, "wrist_l");
  EXPECT_EQ(m.parent_link, "lower_arm_l");
  EXPECT_EQ(m.child_link, "hand_l");
  EXPECT_EQ(m.ragdoll, "ragdoll");
  EXPECT_EQ(m.header.frame_id, "world");
  EXPECT_GE(m.header.stamp, before.stamp);
  EXPECT_GE(m.force, 0.99 * kBreakForce) << "anchor force at the break";
  EXPECT_TRUE(std::isfinite(m.force));

  // The hand moves away from the forearm.
  Snapshot a = g_tf->waitFor(m.header.stamp + ros::Duration(0.2), ros::WallTime(), 20.0);
  ASSERT_TRUE(a.valid());
  // (0.15 s later: the hand, at ~11 m/s, is still in the air; it reaches the ground ~0.4 s
  // after the break)
  Snapshot b = g_tf->waitFor(a.stamp + ros::Duration(0.15), ros::WallTime(), 20.0);
  ASSERT_TRUE(b.valid());
  const double gap_a = gap(a, wrist), gap_b = gap(b, wrist);
  const double speed = (gap_b - gap_a) / (b.stamp - a.stamp).toSec();
  EXPECT_GT(gap_a, 0.3) << "hand still near the wrist 0.2 s after the break";
  EXPECT_GT(speed, 5.0) << "hand not moving away from the forearm";
  EXPECT_EQ(brokenCount(), 1u) << "other joints broke too";
  std::printf("[ break    ] %s broke at +%.4f s sim (force %.1f N); hand-wrist gap %.3f m at +%.3f s, "
              "%.3f m at +%.3f s (%.2f m/s); hand %s -> %s, forearm %s -> %s\n",
              m.joint.c_str(), (m.header.stamp - before.stamp).toSec(), m.force, gap_a,
              (a.stamp - m.header.stamp).toSec(), gap_b, (b.stamp - m.header.stamp).toSec(), speed,
              str(a.position("hand_l")).c_str(), str(b.position("hand_l")).c_str(),
              str(a.position("lower_arm_l")).c_str(), str(b.position("lower_arm_l")).c_str());

  // ~reset puts the ragdoll back together: the wrist holds the hand again.
  std_srvs::Empty empty;
  ASSERT_TRUE(ros::service::call(kNode + "/reset", empty));
  Snapshot r1 = g_tf->waitFor(ros::Time(), ros::WallTime::now() + ros::WallDuration(0.1), 20.0);
  ASSERT_TRUE(r1.valid());
  Snapshot r2 = g_tf->waitFor(r1.stamp + ros::Duration(0.5), ros::WallTime(), 20.0);
  ASSERT_TRUE(r2.valid());
  EXPECT_LT(gap(r1, wrist), 0.005) << "hand not back on the wrist after ~reset";
  EXPECT_LT(gap(r2, wrist), 0.005) << "wrist not holding after ~reset";
  EXPECT_EQ(brokenCount(), 1u);
  std::printf("[ break    ] after ~reset: hand-wrist gap %.5f m, 0.5 s later %.5f m\n", gap(r1, wrist),
              gap(r2, wrist));
  RecordProperty("break_force_reported", std::to_string(m.force));
  RecordProperty("gap_after_break", std::to_string(gap_b));
  RecordProperty("separation_speed", std::to_string(speed));
}

int main(int argc, char** argv) {
  return runRosTests(
      argc, argv, "joint_break_test", 2,
      [] {
        ros::NodeHandle nh;
        g_links = urdfLinks();
        g_tf = std::make_unique<TfSnapshots>(nh, linkNames(g_links));
      },
      [] { g_tf.reset(); });
}
