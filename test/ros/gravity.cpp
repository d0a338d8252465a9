// rostest: ragdoll_sim_node with gravity and the ground plane. After at least 4 s of sim time
// (measured with TF stamps) the ragdoll lies on the ground: pelvis height 0.05..0.4 m, pelvis
// speed < 0.05 m/s, and no link's centre of mass below the ground.
#include <gtest/gtest.h>

#include <memory>

#include "node_log.hpp"
#include "tf_snapshots.hpp"

using namespace ragdoll_test;

namespace {
std::vector<LinkMass> g_links;
std::string g_root;
std::unique_ptr<TfSnapshots> g_tf;
}  // namespace

TEST(Gravity, RagdollComesToRestOnTheGround) {
  ASSERT_GT(g_links.size(), 1u) << "robot_description missing or not a URDF";
  const std::string pelvis = g_root;  // the free-floating root link ("pelvis")

  Snapshot first = g_tf->waitFor(ros::Time(), ros::WallTime(), 30.0);
  ASSERT_TRUE(first.valid()) << "no TF from the node";
  // Stamps are start + sim time, so stamp differences are sim time; the first snapshot seen is
  // at sim time >= 0, hence 5 s after it the sim has run >= 5 s (>= 4 s required).
  Snapshot a = g_tf->waitFor(first.stamp + ros::Duration(5.0), ros::WallTime(), 60.0);
  ASSERT_TRUE(a.valid()) << "sim time did not reach 5 s within 60 s of wall time";
  Snapshot b = g_tf->waitFor(a.stamp + ros::Duration(0.2), ros::WallTime(), 10.0);
  ASSERT_TRUE(b.valid());

  const Vec3 pa = a.position(pelvis), pb = b.position(pelvis);
  const double speed = (pb - pa).norm() / (b.stamp - a.stamp).toSec();
  EXPECT_GE(pb.z(), 0.05) << "pelvis below the expected resting height: " << str(pb);
  EXPECT_LE(pb.z(), 0.4) << "pelvis not lying on the ground: " << str(pb);
  EXPECT_LT(speed, 0.05) << "pelvis still moving at " << speed << " m/s (" << str(pa) << " -> "
                         << str(pb) << " in " << (b.stamp - a.stamp).toSec() << " s)";
  for (const LinkMass& l : g_links) {
    if (l.mass < 0.01) continue;  // massless dummy links of the ball joints
    EXPECT_GT(comOf(b, l).z(), 0.0) << "centre of mass of " << l.name << " below the ground: "
                                    << str(comOf(b, l));
  }
  RecordProperty("pelvis_z", std::to_string(pb.z()));
  RecordProperty("pelvis_speed", std::to_string(speed));
}

int main(int argc, char** argv) {
  return runRosTests(
      argc, argv, "gravity_test", 1,
      [] {
        ros::NodeHandle nh;
        g_links = urdfLinks(&g_root);
        g_tf = std::make_unique<TfSnapshots>(nh, linkNames(g_links));
      },
      [] { g_tf.reset(); });
}
