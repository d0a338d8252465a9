// The anatomy settings of config/joints.yaml, ROS-free: a ball joint's cone / twist (~joints)
// and per-link velocity damping (~link_damping) resolved onto the RagdollDef, and in a Scene's
// World once spawned.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "joint_control.hpp"
#include "link_damping.hpp"
#include "ragdoll_sim/scene.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::scene;

namespace {

// base -(ball sh_y+sh_x+sh_z, URDF Euler limits)- arm -(hinge elbow)- hand
RagdollDef model() {
  RagdollDef def;
  def.name = "arm";
  for (const char* n : {"base", "arm", "hand"}) {
    LinkDef l;
    l.name = n;
    l.mass = 1.0;
    def.links.push_back(l);
  }
  def.links[1].com = Vec3(0.5, 0, 0);
  def.links[1].rest_pose = Transform(Vec3::Zero(), Quat::Identity());
  def.links[2].rest_pose = Transform(Vec3(1.0, 0, 0), Quat::Identity());
  RagdollJointDef sh;
  sh.name = "sh_y+sh_x+sh_z";
  sh.kind = RagdollJointKind::Ball;
  sh.parent = 0;
  sh.child = 1;
  sh.axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  sh.limited = true;
  sh.lower = {-1.0, -1.0, -1.0};
  sh.upper = {1.0, 1.0, 1.0};
  sh.source_joints = {"sh_y", "sh_x", "sh_z"};
  RagdollJointDef elbow;
  elbow.name = "elbow";
  elbow.parent = 1;
  elbow.child = 2;
  elbow.frame_parent = Transform(Vec3(1.0, 0, 0), Quat::Identity());
  elbow.axes = {Vec3::UnitY()};
  elbow.source_joints = {"elbow"};
  def.joints = {sh, elbow};
  return def;
}

JointSettings limits(std::array<double, 2> cone, std::optional<std::array<double, 2>> twist = {}) {
  JointSettings s;
  s.cone = cone;
  s.twist = twist;
  return s;
}

}  // namespace

TEST(AnatomySettings, ConeAndTwistReachTheBall) {
  RagdollDef def = model();
  const AxisTable t(def);
  // By any source joint's name: the whole ball.
  JointSettingsResult r = applyJointSettings(
      &def, t, JointSettings(), {{"sh_x", limits({0.8, 0.5}, std::array<double, 2>{-0.3, 0.2})}},
      MotorGains());
  ASSERT_EQ(r.error, "");
  ASSERT_TRUE(def.joints[0].swing_twist.has_value());
  EXPECT_EQ(def.joints[0].swing_twist->cone_1, 0.8);
  EXPECT_EQ(def.joints[0].swing_twist->cone_2, 0.5);
  EXPECT_EQ(def.joints[0].swing_twist->twist_lower, -0.3);
  EXPECT_EQ(def.joints[0].swing_twist->twist_upper, 0.2);
  // Over a URDF's limits: the cone replaced, the twist kept.
  def = model();
  SwingTwistLimits urdf;
  urdf.twist_lower = -0.1;
  urdf.twist_upper = 0.1;
  def.joints[0].swing_twist = urdf;
  r = applyJointSettings(&def, t, JointSettings(), {{"sh_y+sh_x+sh_z", limits({0.6, 0.6})}},
                         MotorGains());
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(def.joints[0].swing_twist->cone_1, 0.6);
  EXPECT_EQ(def.joints[0].swing_twist->twist_lower, -0.1);
}

TEST(AnatomySettings, HingesConflictsAndBadValuesAreRefusedByName) {
  RagdollDef def = model();
  const AxisTable t(def);
  JointSettingsResult r =
      applyJointSettings(&def, t, JointSettings(), {{"elbow", limits({0.5, 0.5})}}, MotorGains());
  EXPECT_NE(r.error.find("~joints/elbow: cone and twist apply to ball joints only"),
            std::string::npos) << r.error;
  r = applyJointSettings(&def, t, JointSettings(),
                         {{"sh_x", limits({0.5, 0.5})}, {"sh_z", limits({0.4, 0.4})}}, MotorGains());
  EXPECT_NE(r.error.find("~joints/sh_x and ~joints/sh_z both set cone"), std::string::npos)
      << r.error;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const struct {
    JointSettings s;
    const char* message;
  } cases[] = {
      {limits({-0.5, 0.5}), "j/cone[0] must be an angle in (0, pi] rad, got -0.5"},
      {limits({0.5, nan}), "j/cone[1] must be an angle in (0, pi] rad, got nan"},
      {limits({0.5, 3.5}), "j/cone[1] must be an angle in (0, pi] rad, got 3.5"},
      {limits({0.5, 0.5}, std::array<double, 2>{0.3, -0.3}),
       "j/twist[0] must be <= j/twist[1], got 0.3 > -0.3"},
  };
  for (const auto& c : cases)
    EXPECT_NE(validateJointSettings(c.s, "j").find(c.message), std::string::npos)
        << validateJointSettings(c.s, "j");
}

TEST(AnatomySettings, LinkDampingStarThenNamed) {
  RagdollDef def = model();
  def.links[2].linear_damping = 7.0;  // from a URDF dampingFactor
  LinkDamping all, arm;
  all.angular = 0.5;
  arm.linear = 2.0;
  const auto warnings = applyLinkDamping(&def, {{"arm", arm}, {"*", all}, {"leg", arm}});
  EXPECT_EQ(def.links[0].linear_damping, 0.0);
  EXPECT_EQ(def.links[0].angular_damping, 0.5);
  EXPECT_EQ(def.links[1].linear_damping, 2.0);
  EXPECT_EQ(def.links[1].angular_damping, 0.5);
  EXPECT_EQ(def.links[2].linear_damping, 7.0);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("~link_damping/leg"), std::string::npos);
  LinkDamping bad;
  bad.angular = -1.0;
  EXPECT_NE(validateLinkDamping(bad, "p/arm").find("p/arm/angular must be a finite number >= 0"),
            std::string::npos);
}

// Through a Scene: the bodies get the damping, and the cone holds the arm up in the World.
TEST(AnatomySettings, SceneSpawnsWithTheSettings) {
  SceneDef sd;
  sd.ground = false;
  sd.joints = {{"sh_y", limits({0.4, 0.4})}};
  LinkDamping d;
  d.linear = 3.0;
  d.angular = 4.0;
  sd.link_damping = {{"hand", d}};
  Scene scene(sd);
  SpawnDef s;
  s.name = "arm";
  s.def = model();
  s.fixed_base = true;
  std::string e;
  ASSERT_EQ(scene.addRagdoll(s, &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  World& w = scene.world();
  const BodyId hand = scene.bodies(0).bodies[2];
  EXPECT_EQ(w.bodyDef(hand).linear_damping, 3.0);
  EXPECT_EQ(w.bodyDef(hand).angular_damping, 4.0);
  const JointId sh = scene.bodies(0).joints[0];
  for (int i = 0; i < 1500; ++i) w.step(1e-3);
  EXPECT_NEAR(w.ballSwingTwist(sh)[0], 0.4, 0.01);
}
