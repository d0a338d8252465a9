// rostest: a Gazebo SDF world loaded at start-up (~world_file). A the ragdoll dropped over a
// static box of the world lands on it (its lowest shape point stays above the box top) while the
// world's dynamic crate falls to the default ground; B a world with its own plane (1 m below
// z = 0) replaces the default ground; C ~world_strict with a missing include: exit 1 and one
// FATAL naming it; without it a WARN naming it, and the INFO lines of notes and step size; a
// ~gravity set by the user wins over the world's.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "marker_log.hpp"
#include "node_binary.hpp"
#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {

// Lowest world z of a shape marker (sphere, cube, cylinder, triangle list).
double lowestZ(const visualization_msgs::Marker& m) {
  using visualization_msgs::Marker;
  const Eigen::Quaterniond q(m.pose.orientation.w, m.pose.orientation.x, m.pose.orientation.y,
                             m.pose.orientation.z);
  const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
  const Vec3 p(m.pose.position.x, m.pose.position.y, m.pose.position.z);
  switch (m.type) {
    case Marker::SPHERE: return p.z() - 0.5 * m.scale.x;
    case Marker::CUBE:
      return p.z() - 0.5 * (std::abs(R(2, 0)) * m.scale.x + std::abs(R(2, 1)) * m.scale.y +
                            std::abs(R(2, 2)) * m.scale.z);
    case Marker::CYLINDER: {
      const double az = std::min(1.0, std::abs(R(2, 2)));
      return p.z() - (az * 0.5 * m.scale.z + std::sqrt(1.0 - az * az) * 0.5 * m.scale.x);
    }
    case Marker::TRIANGLE_LIST: {
      double z = std::numeric_limits<double>::infinity();
      for (const auto& v : m.points) z = std::min(z, (p + R * Vec3(v.x, v.y, v.z)).z());
      return z;
    }
    default: return std::numeric_limits<double>::infinity();
  }
}

// Lowest point of every shape in marker namespace `ns` of the next ~markers message of `node`.
double lowestPoint(ros::NodeHandle& nh, const std::string& node, const std::string& ns,
                   visualization_msgs::MarkerArray* out = nullptr) {
  MarkerLog log(nh, node + "/markers");
  visualization_msgs::MarkerArray a;
  if (!log.waitFor([&](const auto& m) { return !MarkerLog::inNs(m, ns).empty(); }, &a))
    return std::numeric_limits<double>::quiet_NaN();
  double z = std::numeric_limits<double>::infinity();
  for (const auto* m : MarkerLog::inNs(a, ns)) z = std::min(z, lowestZ(*m));
  if (out) *out = a;
  return z;
}

std::string fixture(const std::string& name) {
  return std::string(RAGDOLL_SIM_SOURCE_DIR) + "/test/ros/worlds/" + name;
}

int runNode(const std::string& name, const std::string& args, int seconds, std::string* out) {
  return runNodeBinary(
      name, std::string("_urdf_file:=") + RAGDOLL_SIM_SOURCE_DIR + "/urdf/ragdoll.urdf " + args,
      seconds, out);
}

}  // namespace

TEST(WorldStart, A_RagdollLandsOnStaticBox) {
  ros::NodeHandle nh;
  SimClient sim("/ragdoll_sim");
  ASSERT_TRUE(sim.waitUp()) << "node did not come up";
  ASSERT_TRUE(sim.step(2000).success);
  visualization_msgs::MarkerArray a;
  const double low = lowestPoint(nh, "/ragdoll_sim", "ragdoll", &a);
  // The box top is z = 0.5: the ragdoll rests on it (5 mm of contact slop at most).
  std::printf("[figure] ragdoll on the static box (top z = 0.5): lowest point z = %.4f m\n", low);
  EXPECT_GT(low, 0.5 - 0.005);
  EXPECT_LT(low, 0.5 + 0.05);
  // The world's static box is drawn in its SDF colour, darkened; the dynamic crate fell to
  // the default ground beside it.
  const auto table = MarkerLog::inNs(a, "table");
  ASSERT_EQ(table.size(), 1u);
  EXPECT_NEAR(table[0]->color.r, 0.6 * 0.6, 1e-3);
  EXPECT_NEAR(table[0]->color.g, 0.4 * 0.6, 1e-3);
  const auto crate = sim.link("crate", "body");
  ASSERT_TRUE(crate.success) << crate.message;
  EXPECT_NEAR(position(crate).z(), 0.1, 0.01);
}

TEST(WorldStart, B_WorldPlaneReplacesGround) {
  ros::NodeHandle nh;
  SimClient sim("/plane_sim");
  ASSERT_TRUE(sim.waitUp()) << "node did not come up";
  ASSERT_TRUE(sim.step(2000).success);
  const double low = lowestPoint(nh, "/plane_sim", "ragdoll");
  // Through z = 0 (no default plane) onto the world's plane at z = -1.
  std::printf("[figure] ragdoll on the world's plane (z = -1): lowest point z = %.4f m\n", low);
  EXPECT_NEAR(low, -1.0, 0.01);
}

TEST(WorldStart, C_StrictMissingInclude) {
  std::string out;
  ros::WallTime t0 = ros::WallTime::now();
  int rc = runNode("strict_node", "_world_file:=" + fixture("missing_include.world") +
                                      " _world_strict:=true", 60, &out);
  EXPECT_EQ(rc, 1) << out;
  std::printf("[figure] ~world_strict, missing include: exit %d after %.2f s\n", rc,
              (ros::WallTime::now() - t0).toSec());
  EXPECT_LT((ros::WallTime::now() - t0).toSec(), 20.0);
  EXPECT_NE(out.find("FATAL"), std::string::npos) << out;
  EXPECT_NE(out.find("no_such_model_anywhere"), std::string::npos) << out;
  EXPECT_NE(out.find("~world_strict"), std::string::npos) << out;

  // Not strict: it runs (stopped by `timeout`: 124), with a WARN naming the include.
  rc = runNode("lenient_node", "_world_file:=" + fixture("missing_include.world"), 8, &out);
  EXPECT_EQ(rc, 124) << out;
  EXPECT_EQ(out.find("FATAL"), std::string::npos) << out;
  EXPECT_NE(out.find("no_such_model_anywhere"), std::string::npos) << out;
  EXPECT_NE(out.find("WARN"), std::string::npos) << out;

  // Notes of what is not simulated and the step size, as INFO; a ~gravity other than the
  // default wins over the world's; a missing file is FATAL.
  // A list cannot be given on a command line: set before the node starts.
  ros::param::set("/notes_node/gravity", std::vector<double>{0.0, 0.0, -1.62});
  rc = runNode("notes_node", "_world_file:=" + fixture("box_world.world"), 8, &out);
  ros::param::del("/notes_node/gravity");
  EXPECT_EQ(rc, 124) << out;
  EXPECT_NE(out.find("max_step_size"), std::string::npos) << out;
  EXPECT_NE(out.find("0.004"), std::string::npos) << out;
  EXPECT_NE(out.find("light"), std::string::npos) << out;
  EXPECT_NE(out.find("world=box_world status=ok"), std::string::npos) << out;
  EXPECT_NE(out.find("replaced by ~gravity"), std::string::npos) << out;
  EXPECT_NE(out.find("gravity (0.00, 0.00, -1.62)"), std::string::npos) << out;
  rc = runNode("missing_node", "_world_file:=/nonexistent/x.world", 60, &out);
  EXPECT_EQ(rc, 1) << out;
  EXPECT_NE(out.find("/nonexistent/x.world"), std::string::npos) << out;
}

int main(int argc, char** argv) {
  return ragdoll_test::runRosTests(argc, argv, "world_start_test", 1, [] {}, [] {});
}
