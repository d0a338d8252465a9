// URDFs from the wild: joint types (prismatic, spherical, preserved fixed, planar / floating
// refused, mimic reported), capsules, <gazebo> friction, massless and placeholder links,
// inertia repairs, chains that cannot fold into a ball, limits past +-pi.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>

#include "ragdoll_sim/drop_check.hpp"
#include "ragdoll_sim/urdf_loader.hpp"

using namespace ragdoll_sim;

namespace {

std::string inertial(double m, const std::string& I = "ixx='0.01' iyy='0.01' izz='0.01'") {
  return "<inertial><mass value='" + std::to_string(m) + "'/><inertia " + I +
         " ixy='0' ixz='0' iyz='0'/></inertial>";
}
std::string ulink(const std::string& name, const std::string& body) {
  return "<link name='" + name + "'>" + body + "</link>";
}
std::string box(const std::string& size) {
  return "<collision><geometry><box size='" + size + "'/></geometry></collision>";
}
std::string joint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child, const std::string& xyz = "0 0 -0.3",
                  const std::string& axis = "0 1 0", const std::string& extra =
                      "<limit lower='-1' upper='1' effort='1' velocity='1'/>") {
  return "<joint name='" + name + "' type='" + type + "'><parent link='" + parent +
         "'/><child link='" + child + "'/><origin xyz='" + xyz + "'/><axis xyz='" + axis + "'/>" +
         extra + "</joint>";
}
std::string robot(const std::string& body) { return "<robot name='t'>" + body + "</robot>"; }

int countContaining(const std::vector<std::string>& v, const std::vector<std::string>& words) {
  return int(std::count_if(v.begin(), v.end(), [&](const std::string& s) {
    return std::all_of(words.begin(), words.end(),
                       [&](const std::string& w) { return s.find(w) != std::string::npos; });
  }));
}

const RagdollJointDef* findJoint(const RagdollDef& d, const std::string& name) {
  for (const RagdollJointDef& j : d.joints)
    if (j.name == name) return &j;
  return nullptr;
}

}  // namespace

TEST(UrdfFormats, CapsuleBecomesACapsule) {
  const UrdfLoadResult r = loadUrdfString(robot(ulink(
      "a", inertial(1) + "<collision><origin xyz='0 0 0.1'/><geometry><capsule radius='0.05' length='0.3'/>"
                         "</geometry></collision>")));
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.def.links[0].shapes.size(), 1u);
  const Geometry& g = r.def.links[0].shapes[0].geometry;
  EXPECT_EQ(g.type, ShapeType::Capsule);
  EXPECT_DOUBLE_EQ(g.radius, 0.05);
  EXPECT_DOUBLE_EQ(g.half_height, 0.15);  // URDF length: the cylinder part
  EXPECT_EQ(r.def.links[0].shape_sources.at(0), "capsule");
}

TEST(UrdfFormats, PrismaticJointSlidesWithinItsLimits) {
  const UrdfLoadResult r = loadUrdfString(robot(
      ulink("base", inertial(5) + box("0.2 0.2 0.2")) + ulink("slider", inertial(1) + box("0.1 0.1 0.1")) +
      joint("slide", "prismatic", "base", "slider", "0 0 -0.3", "0 0 1",
            "<limit lower='-0.2' upper='0.1' effort='1' velocity='1'/><dynamics damping='3' friction='0.5'/>")));
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.def.joints.size(), 1u);
  const RagdollJointDef& j = r.def.joints[0];
  EXPECT_EQ(j.kind, RagdollJointKind::Prismatic);
  EXPECT_TRUE(j.limited);
  EXPECT_DOUBLE_EQ(j.lower[0], -0.2);
  EXPECT_DOUBLE_EQ(j.upper[0], 0.1);
  EXPECT_EQ(j.damping, (std::vector<double>{3.0}));
  EXPECT_EQ(j.friction, (std::vector<double>{0.5}));
  // Hung from a fixed base in gravity along the axis, the slider drops to its lower limit.
  WorldDef wd;
  World world(wd);
  const Ragdoll rd = spawnRagdoll(world, r.def, Transform(Vec3(0, 0, 2), Quat::Identity()));
  BodyDef anchor;
  anchor.type = BodyType::Static;
  FixedJointDef weld;
  weld.body_a = world.createBody(anchor);
  weld.body_b = rd.bodies[0];
  weld.frame_a = Transform(Vec3(0, 0, 2), Quat::Identity());
  world.createFixedJoint(weld);
  EXPECT_EQ(world.jointType(rd.joints[0]), JointType::Prismatic);
  for (int s = 0; s < 2000; ++s) world.step(1e-3);
  EXPECT_NEAR(world.prismaticPosition(rd.joints[0]), -0.2, 0.005);
  EXPECT_LT(world.jointAnchorError(rd.joints[0]).norm(), 1e-3);
}

TEST(UrdfFormats, SphericalJointIsAFreeBall) {
  const UrdfLoadResult r = loadUrdfString(robot(
      ulink("a", inertial(2) + box("0.2 0.2 0.2")) + ulink("b", inertial(1) + box("0.1 0.1 0.1")) +
      joint("neck", "spherical", "a", "b", "0 0 0.3", "0 0 1", "<dynamics damping='0.2'/>")));
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.def.joints.size(), 1u);
  const RagdollJointDef& j = r.def.joints[0];
  EXPECT_EQ(j.kind, RagdollJointKind::Ball);
  EXPECT_FALSE(j.limited);
  EXPECT_EQ(j.axes.size(), 3u);
  EXPECT_EQ(j.damping, (std::vector<double>(3, 0.2)));
  EXPECT_LT((r.def.links[1].rest_pose.p - Vec3(0, 0, 0.3)).norm(), 1e-12);
}

TEST(UrdfFormats, FixedJointsLumpUnlessPreserved) {
  const std::string body = ulink("a", inertial(2) + box("0.2 0.2 0.2")) +
                           ulink("b", inertial(1) + box("0.1 0.1 0.1")) + joint("weld", "fixed", "a", "b");
  const UrdfLoadResult lumped = loadUrdfString(robot(body));
  ASSERT_TRUE(lumped.ok) << lumped.error;
  EXPECT_EQ(lumped.def.links.size(), 1u);
  EXPECT_DOUBLE_EQ(lumped.def.links[0].mass, 3.0);
  EXPECT_NEAR(lumped.def.links[0].com.z(), -0.1, 1e-12);  // (2*0 + 1*-0.3) / 3
  const UrdfLoadResult kept = loadUrdfString(
      robot(body + "<gazebo reference='weld'><preserveFixedJoint>true</preserveFixedJoint></gazebo>"));
  ASSERT_TRUE(kept.ok) << kept.error;
  ASSERT_EQ(kept.def.links.size(), 2u);
  ASSERT_EQ(kept.def.joints.size(), 1u);
  EXPECT_EQ(kept.def.joints[0].kind, RagdollJointKind::Fixed);
  World world;
  const Ragdoll rd = spawnRagdoll(world, kept.def, Transform());
  EXPECT_EQ(world.jointType(rd.joints[0]), JointType::Fixed);
}

TEST(UrdfFormats, MimicIsReportedAndMasslessLinksAreLumped) {
  const UrdfLoadResult r = loadUrdfString(robot(
      ulink("a", inertial(2) + box("0.2 0.2 0.2")) + ulink("b", inertial(1) + box("0.1 0.1 0.1")) +
      ulink("c", inertial(1) + box("0.1 0.1 0.1")) + ulink("tool_tip", "") +
      ulink("sensor", inertial(1e-6, "ixx='1e-9' iyy='1e-9' izz='1e-9'")) +
      joint("j1", "revolute", "a", "b") +
      joint("j2", "revolute", "a", "c", "0 0.3 0", "0 1 0",
            "<limit lower='-1' upper='1' effort='1' velocity='1'/><mimic joint='j1'/>") +
      joint("tip", "continuous", "b", "tool_tip") + joint("imu", "revolute", "c", "sensor")));
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.def.links.size(), 3u);  // tool_tip and the 1 mg sensor lumped
  EXPECT_EQ(r.def.findLink("tool_tip"), -1);
  EXPECT_EQ(r.def.findLink("sensor"), -1);
  EXPECT_EQ(countContaining(r.def.warnings, {"'j2'", "mimic", "'j1'"}), 1);
  EXPECT_EQ(countContaining(r.def.notes, {"'tip'", "massless"}), 1);
  EXPECT_EQ(countContaining(r.def.notes, {"'imu'", "massless"}), 1);
}

TEST(UrdfFormats, GazeboFrictionReachesTheShapes) {
  const UrdfLoadResult r = loadUrdfString(robot(
      ulink("a", inertial(2) + box("0.2 0.2 0.2")) + ulink("b", inertial(1) + box("0.1 0.1 0.1")) +
      joint("j", "revolute", "a", "b") +
      "<gazebo reference='b'><mu1>0.3</mu1><mu2>0.5</mu2></gazebo>"));
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.def.links[0].shape_friction, (std::vector<double>{-1.0}));
  EXPECT_EQ(r.def.links[1].shape_friction, (std::vector<double>{0.4}));
  EXPECT_EQ(countContaining(r.def.warnings, {"'b'", "mu1"}) + countContaining(r.def.notes, {"'b'", "mu1"}), 1);
  // spawnRagdoll keeps the URDF friction over a blanket material, and only there.
  World world;
  Material rubber;
  rubber.static_friction = rubber.kinetic_friction = 1.1;
  const Ragdoll rd = spawnRagdoll(world, r.def, Transform(), &rubber);
  EXPECT_DOUBLE_EQ(world.bodyShapes(rd.bodies[0])[0].material.static_friction, 1.1);
  EXPECT_DOUBLE_EQ(world.bodyShapes(rd.bodies[1])[0].material.static_friction, 0.4);
  EXPECT_DOUBLE_EQ(world.bodyShapes(rd.bodies[1])[0].material.kinetic_friction, 0.4);
}

TEST(UrdfFormats, UnphysicalInertiasAreRepairedAndReported) {
  // Not positive definite (izz = 0) and violating the triangle inequality (0.01 + 0.01 < 0.05).
  const UrdfLoadResult r = loadUrdfString(robot(
      ulink("a", inertial(2, "ixx='0.01' iyy='0.01' izz='0'") + box("0.2 0.2 0.2")) +
      ulink("b", inertial(1, "ixx='0.01' iyy='0.01' izz='0.05'") + box("0.1 0.1 0.1")) +
      joint("j", "revolute", "a", "b")));
  ASSERT_TRUE(r.ok) << r.error;
  for (const LinkDef& l : r.def.links) {
    const Vec3 e = Eigen::SelfAdjointEigenSolver<Mat3>(l.inertia).eigenvalues();
    EXPECT_GT(e[0], 0) << l.name;
    EXPECT_GE(e[0] + e[1], e[2] * (1 - 1e-9)) << l.name;
  }
  EXPECT_EQ(countContaining(r.def.warnings, {"'a'", "not positive definite", "repaired"}), 1);
  EXPECT_EQ(countContaining(r.def.warnings, {"'b'", "triangle inequality", "repaired"}), 1);
}

TEST(UrdfFormats, UnrepairableInputIsRefusedNamingTheElement) {
  const std::string ab = ulink("a", inertial(2) + box("0.2 0.2 0.2"));
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {robot(ab + ulink("b", inertial(-1) + box("0.1 0.1 0.1")) + joint("j", "revolute", "a", "b")),
       {"'b'", "negative"}},
      {robot(ab + ulink("b", inertial(1) + box("0.1 0.1 0.1")) +
             joint("j", "revolute", "a", "b", "0 0 -0.3", "0 1 0",
                   "<limit lower='1' upper='-1' effort='1' velocity='1'/>")),
       {"'j'", "lower", "upper"}},
  };
  for (const auto& [xml, words] : cases) {
    const UrdfLoadResult r = loadUrdfString(xml);
    ASSERT_FALSE(r.ok) << xml;
    for (const std::string& w : words) EXPECT_NE(r.error.find(w), std::string::npos) << r.error;
  }
}

TEST(UrdfFormats, OffsetChainKeepsHingesWithANominalMassBetween) {
  // A universal joint with 4 cm between its axes (bullet's humanoid ankle) cannot be a ball.
  const UrdfLoadResult r = loadUrdfString(robot(
      ulink("shin", inertial(3) + box("0.1 0.1 0.4")) + ulink("mid", "") +
      ulink("foot", inertial(1) + box("0.2 0.1 0.05")) +
      joint("ank_y", "continuous", "shin", "mid", "0 0 -0.3", "0 1 0", "") +
      joint("ank_x", "continuous", "mid", "foot", "0 0 -0.04", "1 0 0", "")));
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.def.joints.size(), 2u);
  EXPECT_EQ(r.def.joints[0].kind, RagdollJointKind::Hinge);
  EXPECT_EQ(r.def.joints[1].kind, RagdollJointKind::Hinge);
  const int mid = r.def.findLink("mid");
  ASSERT_GE(mid, 0);
  EXPECT_NEAR(r.def.links[mid].mass, 0.1, 1e-12);  // 10 % of the lighter neighbour
  EXPECT_EQ(countContaining(r.def.warnings, {"ank_y+ank_x", "translated origin"}), 1);
  EXPECT_EQ(countContaining(r.def.warnings, {"'mid'", "given 0.1 kg"}), 1);
  EXPECT_LT((r.def.links[r.def.findLink("foot")].rest_pose.p - Vec3(0, 0, -0.34)).norm(), 1e-12);
}

TEST(UrdfFormats, LimitsPastPiAreClippedOrDropped) {
  const UrdfLoadResult r = loadUrdfString(robot(
      ulink("a", inertial(2) + box("0.2 0.2 0.2")) + ulink("b", inertial(1) + box("0.1 0.1 0.1")) +
      ulink("c", inertial(1) + box("0.1 0.1 0.1")) +
      joint("wide", "revolute", "a", "b", "0 0 -0.3", "0 1 0",
            "<limit lower='-1.3' upper='4.45' effort='1' velocity='1'/>") +
      joint("turn", "revolute", "a", "c", "0 0 0.3", "0 1 0",
            "<limit lower='-3.2' upper='3.2' effort='1' velocity='1'/>")));
  ASSERT_TRUE(r.ok) << r.error;
  const RagdollJointDef* wide = findJoint(r.def, "wide");
  const RagdollJointDef* turn = findJoint(r.def, "turn");
  ASSERT_TRUE(wide && turn);
  EXPECT_TRUE(wide->limited);
  EXPECT_DOUBLE_EQ(wide->lower[0], -1.3);
  EXPECT_NEAR(wide->upper[0], M_PI - 0.05, 1e-12);
  EXPECT_FALSE(turn->limited);
  EXPECT_EQ(countContaining(r.def.warnings, {"'wide'", "clipped"}), 1);
  EXPECT_EQ(countContaining(r.def.warnings, {"'turn'", "full turn"}), 1);
}

TEST(UrdfFormats, OverlappingLinksAtRestDoNotCollide) {
  // a - b - c in a row; c's box reaches back into a: the pair is excluded, named in a note.
  const UrdfLoadResult r = loadUrdfString(robot(
      ulink("a", inertial(2) + box("0.2 0.2 0.2")) + ulink("b", inertial(1) + box("0.05 0.05 0.05")) +
      ulink("c", inertial(1) + "<collision><origin xyz='0 0 0.25'/><geometry><box size='0.1 0.1 0.3'/></geometry></collision>") +
      joint("j1", "revolute", "a", "b", "0 0 -0.2") + joint("j2", "revolute", "b", "c", "0 0 -0.2")));
  ASSERT_TRUE(r.ok) << r.error;
  const int a = r.def.findLink("a"), c = r.def.findLink("c");
  EXPECT_EQ(std::count(r.def.no_collide.begin(), r.def.no_collide.end(), std::make_pair(std::min(a, c), std::max(a, c))), 1);
  EXPECT_EQ(countContaining(r.def.notes, {"overlapping", "a/c"}), 1);
}
