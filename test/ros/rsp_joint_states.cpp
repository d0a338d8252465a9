// rostest: robot_state_publisher accepts our /joint_states. For every URDF joint (revolute, and
// fixed: our TF carries the links the loader lumped into bodies) it publishes
// parent -> child from our joint positions; that must equal the same transform taken from our
// own TF (sim/parent -> sim/child) at the same stamp, up to the solver's joint error (the
// bodies' relative rotation off the joint's own axes, ~1e-4 rad in a fall, which joint angles
// can not express).
#include <gtest/gtest.h>

#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <urdf_parser/urdf_parser.h>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {

Eigen::Isometry3d toEigen(const geometry_msgs::TransformStamped& t) {
  Eigen::Isometry3d e = Eigen::Isometry3d::Identity();
  e.translation() = Vec3(t.transform.translation.x, t.transform.translation.y, t.transform.translation.z);
  e.linear() = Eigen::Quaterniond(t.transform.rotation.w, t.transform.rotation.x,
                                  t.transform.rotation.y, t.transform.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  return e;
}

}  // namespace

TEST(RspJointStates, PublishesEveryLinkFromOurJointStates) {
  ASSERT_TRUE(SimClient("/ragdoll_sim").waitUp()) << "node did not come up";
  std::string xml;
  ASSERT_TRUE(ros::param::get("/robot_description", xml));
  urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
  ASSERT_TRUE(model);
  tf2_ros::Buffer buffer(ros::Duration(30.0));
  tf2_ros::TransformListener listener(buffer);
  // Let it fall for 1.5 s of sim time (stamps are start time + sim time) so the joints bend.
  std::string err;
  ASSERT_TRUE(buffer.canTransform("world", "sim/pelvis", ros::Time(0), ros::Duration(20.0), &err)) << err;
  const ros::Time start = buffer.lookupTransform("world", "sim/pelvis", ros::Time(0)).header.stamp;
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::WallTime::now() < deadline &&
         buffer.lookupTransform("world", "sim/pelvis", ros::Time(0)).header.stamp < start + ros::Duration(1.5))
    ros::WallDuration(0.05).sleep();

  int compared = 0, bent = 0, fixed_compared = 0;
  double worst = 0.0;
  for (const auto& [name, joint] : model->joints_) {
    const bool fixed = joint->type == urdf::Joint::FIXED;  // a lumped link: a fixed frame on TF
    if (joint->type != urdf::Joint::REVOLUTE && joint->type != urdf::Joint::CONTINUOUS && !fixed)
      continue;
    const std::string& parent = joint->parent_link_name;
    const std::string& child = joint->child_link_name;
    EXPECT_TRUE(buffer.canTransform(parent, child, ros::Time(0), ros::Duration(10.0), &err))
        << "robot_state_publisher published no " << parent << " -> " << child << " (joint " << name
        << "): " << err;
    if (!buffer.canTransform(parent, child, ros::Time(0))) continue;
    const auto theirs = buffer.lookupTransform(parent, child, ros::Time(0));
    const ros::Time t = theirs.header.stamp;
    ASSERT_TRUE(buffer.canTransform("sim/" + parent, "sim/" + child, t, ros::Duration(5.0), &err))
        << "our TF has no sim/" << parent << " -> sim/" << child << " at " << t << ": " << err;
    const auto ours = buffer.lookupTransform("sim/" + parent, "sim/" + child, t);
    const Eigen::Isometry3d a = toEigen(theirs), b = toEigen(ours);
    const double dp = (a.translation() - b.translation()).norm();
    const double dr = Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
    worst = std::max(worst, std::max(dp, dr));
    EXPECT_LT(dp, 1e-3) << name << ": translation differs by " << dp << " m";
    EXPECT_LT(dr, 2e-3) << name << ": rotation differs by " << dr << " rad";
    if (Eigen::AngleAxisd(a.linear()).angle() > 0.01) ++bent;
    ++compared;
    fixed_compared += fixed;
  }
  EXPECT_GE(compared, 20);
  EXPECT_GE(fixed_compared, 1) << "the bundled ragdoll's fixed head_camera frame was not compared";
  EXPECT_GE(bent, 3) << "the joints did not move: the comparison proves little";
  std::printf("[ rsp      ] %d joints compared (%d fixed), %d bent by > 0.01 rad, worst difference "
              "%.3g\n", compared, fixed_compared, bent, worst);
}

int main(int argc, char** argv) {
  return runRosTests(argc, argv, "rsp_joint_states_test", 2, [] {}, [] {});
}
