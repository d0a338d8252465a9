// Unit tests of the node's ROS-free joint control (src/scene/joint_control.*): axis names,
// ~joints settings resolution, ~target_pose checks and the motors it makes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "joint_control.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::scene;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// pelvis -(ball waist_y+waist_x+waist_z)- torso -(hinge elbow)- arm -(2-joint ball hip_y+hip_x)- leg
RagdollDef model() {
  RagdollDef def;
  def.name = "test";
  for (const char* n : {"pelvis", "torso", "arm", "leg"}) {
    LinkDef l;
    l.name = n;
    def.links.push_back(l);
  }
  RagdollJointDef waist;
  waist.name = "waist_y+waist_x+waist_z";
  waist.kind = RagdollJointKind::Ball;
  waist.parent = 0;
  waist.child = 1;
  waist.axes = {Vec3::UnitY(), Vec3::UnitX(), Vec3::UnitZ()};
  waist.limited = true;
  waist.lower = {-0.5, -0.4, -0.3};
  waist.upper = {1.0, 0.4, 0.3};
  waist.source_joints = {"waist_y", "waist_x", "waist_z"};
  waist.damping = {0.1, 0.2, 0.3};
  RagdollJointDef elbow;
  elbow.name = "elbow";
  elbow.parent = 1;
  elbow.child = 2;
  elbow.axes = {-Vec3::UnitY()};
  elbow.limited = true;
  elbow.lower = {0.0};
  elbow.upper = {2.6};
  elbow.source_joints = {"elbow"};
  elbow.damping = {0.5};
  elbow.friction = {2.0};
  RagdollJointDef hip;
  hip.name = "hip_y+hip_x";
  hip.kind = RagdollJointKind::Ball;
  hip.parent = 0;
  hip.child = 3;
  hip.axes = {Vec3::UnitY(), Vec3::UnitX(), Vec3::UnitZ()};
  hip.source_joints = {"hip_y", "hip_x"};
  def.joints = {waist, elbow, hip};
  return def;
}

JointSettings breakAt(double f) {
  JointSettings s;
  s.break_force = f;
  return s;
}

}  // namespace

TEST(AxisTable, NamesAreTheJointStateNames) {
  const RagdollDef def = model();
  const AxisTable t(def);
  ASSERT_EQ(t.size(), 7);
  const char* names[] = {"waist_y", "waist_x", "waist_z", "elbow", "hip_y", "hip_x", "hip_y+hip_x_2"};
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(t[i].name, names[i]);
    EXPECT_EQ(t.find(names[i]), i);
  }
  EXPECT_EQ(t.find("waist_y+waist_x+waist_z"), -1);  // a joint, not an axis
  EXPECT_EQ(t.find("nope"), -1);
  EXPECT_EQ(t[1].joint, 0);
  EXPECT_EQ(t[1].axis, 1);
  EXPECT_TRUE(t[1].limited);
  EXPECT_DOUBLE_EQ(t[1].lower, -0.4);
  EXPECT_DOUBLE_EQ(t[1].upper, 0.4);
  EXPECT_FALSE(t[4].limited);
  EXPECT_EQ(t.first(1), 3);
  EXPECT_EQ(t.count(0), 3);
  EXPECT_EQ(t.count(1), 1);
  EXPECT_EQ(t.count(2), 3);
}

TEST(AxisTable, SliderHasOneAxisWeldNoneSphericalThree) {
  RagdollDef def = model();
  LinkDef extra;
  for (const char* n : {"slider", "welded", "head"}) {
    extra.name = n;
    def.links.push_back(extra);
  }
  RagdollJointDef slide, weld, neck;
  slide.name = "slide";
  slide.kind = RagdollJointKind::Prismatic;
  slide.source_joints = {"slide"};
  slide.axes = {Vec3::UnitZ()};
  weld.name = "weld";
  weld.kind = RagdollJointKind::Fixed;
  weld.source_joints = {"weld"};
  neck.name = "neck";  // URDF spherical: one source joint, three axes
  neck.kind = RagdollJointKind::Ball;
  neck.source_joints = {"neck"};
  neck.axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  def.joints.push_back(slide);
  def.joints.push_back(weld);
  def.joints.push_back(neck);
  const AxisTable t(def);
  ASSERT_EQ(t.size(), 7 + 1 + 0 + 3);
  EXPECT_EQ(t.count(3), 1);
  EXPECT_EQ(t.count(4), 0);
  EXPECT_EQ(t.count(5), 3);
  EXPECT_EQ(t.find("slide"), 7);
  EXPECT_EQ(t.find("weld"), -1);
  EXPECT_EQ(t.find("neck"), 8);
  EXPECT_EQ(t.find("neck_1"), 9);
  EXPECT_EQ(t.find("neck_2"), 10);
}

TEST(JointSettings, ValidationNamesTheField) {
  JointSettings s;
  EXPECT_EQ(validateJointSettings(s, "x"), "");
  s.break_force = kInf;
  s.stiffness = 0.0;
  EXPECT_EQ(validateJointSettings(s, "x"), "");
  s.break_force = 0.0;
  EXPECT_NE(validateJointSettings(s, "x").find("x/break_force"), std::string::npos);
  s.break_force = 10.0;
  s.break_torque = -2.0;
  EXPECT_NE(validateJointSettings(s, "x").find("x/break_torque"), std::string::npos);
  s.break_torque = kInf;
  EXPECT_EQ(validateJointSettings(s, "x"), "");
  s.stiffness = -1.0;
  EXPECT_NE(validateJointSettings(s, "x").find("x/stiffness"), std::string::npos);
  s.stiffness = 1.0;
  s.damping = kNaN;
  EXPECT_NE(validateJointSettings(s, "x").find("x/damping"), std::string::npos);
  s.damping = 1.0;
  s.hertz = 0.0;
  EXPECT_NE(validateJointSettings(s, "x").find("x/motor/hertz"), std::string::npos);
  s.hertz = 10.0;
  s.max_torque = kInf;
  EXPECT_NE(validateJointSettings(s, "x").find("x/motor/max_torque"), std::string::npos);
  EXPECT_NE(validateMotorGains({0.0, 1.0, 1.0}, "m").find("m/hertz"), std::string::npos);
  EXPECT_NE(validateMotorGains({1.0, -1.0, 1.0}, "m").find("m/damping_ratio"), std::string::npos);
  EXPECT_EQ(validateMotorGains(MotorGains(), "m"), "");
}

TEST(JointSettings, DefaultsEntriesAndBallSourceNames) {
  RagdollDef def = model();
  const AxisTable t(def);
  JointSettings defaults;
  defaults.break_force = 1000.0;
  defaults.break_torque = 400.0;
  JointSettings elbow;
  elbow.stiffness = 5e4;
  elbow.damping = 10.0;
  elbow.break_torque = 80.0;
  const JointSettingsResult r =
      applyJointSettings(&def, t, defaults, {{"elbow", elbow}, {"waist_x", breakAt(50.0)}}, MotorGains());
  EXPECT_EQ(r.error, "");
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_DOUBLE_EQ(def.joints[0].spring.break_force, 50.0);  // a source joint names its ball
  EXPECT_DOUBLE_EQ(def.joints[0].spring.stiffness, 0.0);
  EXPECT_DOUBLE_EQ(def.joints[1].spring.stiffness, 5e4);
  EXPECT_DOUBLE_EQ(def.joints[1].spring.damping, 10.0);
  EXPECT_DOUBLE_EQ(def.joints[1].spring.break_force, 1000.0);  // default kept
  EXPECT_DOUBLE_EQ(def.joints[2].spring.break_force, 1000.0);
  EXPECT_DOUBLE_EQ(def.joints[1].spring.break_torque, 80.0);
  EXPECT_DOUBLE_EQ(def.joints[0].spring.break_torque, 400.0);  // default kept
}

TEST(JointSettings, UnknownNamesWarnAndConflictsFail) {
  RagdollDef def = model();
  const AxisTable t(def);
  JointSettingsResult r = applyJointSettings(&def, t, JointSettings(), {{"wrist", breakAt(5.0)}},
                                             MotorGains());
  EXPECT_EQ(r.error, "");
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("wrist"), std::string::npos);
  EXPECT_TRUE(std::isinf(def.joints[0].spring.break_force));

  r = applyJointSettings(&def, t, JointSettings(),
                         {{"waist_x", breakAt(5.0)}, {"waist_z", breakAt(6.0)}}, MotorGains());
  EXPECT_NE(r.error.find("waist_x"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("waist_z"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("break_force"), std::string::npos) << r.error;
}

TEST(JointSettings, MotorGainsPrecedence) {
  RagdollDef def = model();
  const AxisTable t(def);
  MotorGains motor{100.0, 1.0, 500.0};
  JointSettings defaults;
  defaults.max_torque = 400.0;
  JointSettings whole;  // the whole waist ball
  whole.hertz = 50.0;
  JointSettings axis;   // one waist axis
  axis.hertz = 20.0;
  axis.damping_ratio = 0.5;
  JointSettings elbow;
  elbow.max_torque = 30.0;
  const JointSettingsResult r = applyJointSettings(
      &def, t, defaults,
      {{"elbow", elbow}, {"waist_y+waist_x+waist_z", whole}, {"waist_z", axis}}, motor);
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.gains.size(), 7u);
  EXPECT_DOUBLE_EQ(r.gains[0].hertz, 50.0);
  EXPECT_DOUBLE_EQ(r.gains[0].max_torque, 400.0);
  EXPECT_DOUBLE_EQ(r.gains[2].hertz, 20.0);
  EXPECT_DOUBLE_EQ(r.gains[2].damping_ratio, 0.5);
  EXPECT_DOUBLE_EQ(r.gains[3].max_torque, 30.0);
  EXPECT_DOUBLE_EQ(r.gains[3].hertz, 100.0);
  EXPECT_DOUBLE_EQ(r.gains[4].hertz, 100.0);
  EXPECT_DOUBLE_EQ(r.gains[4].max_torque, 400.0);
}

TEST(TargetPose, RejectsBadCommands) {
  const RagdollDef def = model();
  const AxisTable t(def);
  auto error = [&](const TargetPoseCommand& c) {
    const TargetPoseCheck k = checkTargetPose(c, t);
    EXPECT_FALSE(k.ok);
    return k.error;
  };
  EXPECT_NE(error({{}, {}, {}}).find("no joint names"), std::string::npos);
  EXPECT_NE(error({{"elbow", "knee"}, {1.0, 0.5}, {}}).find("'knee'"), std::string::npos);
  EXPECT_NE(error({{"elbow", "elbow"}, {1.0, 0.5}, {}}).find("twice"), std::string::npos);
  EXPECT_NE(error({{"elbow", "waist_y"}, {1.0}, {}}).find("positions"), std::string::npos);
  EXPECT_NE(error({{"elbow"}, {1.0}, {1.0, 2.0}}).find("velocities"), std::string::npos);
  EXPECT_NE(error({{"elbow"}, {}, {}}).find("neither"), std::string::npos);
  EXPECT_NE(error({{"elbow", "hip_x"}, {1.0, kNaN}, {}}).find("position of 'hip_x' is not finite"),
            std::string::npos);
  EXPECT_NE(error({{"elbow"}, {1.0}, {kInf}}).find("velocity of 'elbow' is not finite"),
            std::string::npos);
  EXPECT_NE(error({{"waist_y+waist_x+waist_z"}, {0.1}, {}}).find("unknown joint"), std::string::npos);
  // One throttle key per rule.
  auto problem = [&](const TargetPoseCommand& c) { return checkTargetPose(c, t).problem; };
  EXPECT_EQ(problem({{}, {}, {}}), "no names");
  EXPECT_EQ(problem({{"elbow", "knee"}, {1.0, 0.5}, {}}), "unknown joint");
  EXPECT_EQ(problem({{"elbow", "elbow"}, {1.0, 0.5}, {}}), "repeated joint");
  EXPECT_EQ(problem({{"elbow", "waist_y"}, {1.0}, {}}), "positions length");
  EXPECT_EQ(problem({{"elbow"}, {1.0}, {1.0, 2.0}}), "velocities length");
  EXPECT_EQ(problem({{"elbow"}, {}, {}}), "no values");
  EXPECT_EQ(problem({{"elbow"}, {kNaN}, {}}), "position not finite");
  EXPECT_EQ(problem({{"elbow"}, {1.0}, {kInf}}), "velocity not finite");
}

TEST(TargetPose, PositionVelocityAndClamp) {
  const RagdollDef def = model();
  const AxisTable t(def);
  const TargetPoseCommand cmd{{"waist_x", "elbow", "hip_y+hip_x_2"}, {0.9, 1.2, 0.0}, {0.0, -0.5, 0.0}};
  const TargetPoseCheck k = checkTargetPose(cmd, t);
  ASSERT_TRUE(k.ok) << k.error;
  EXPECT_EQ(k.axes, (std::vector<int>{1, 3, 6}));
  ASSERT_EQ(k.clamped.size(), 1u);
  EXPECT_EQ(k.clamped[0], "waist_x");  // 0.9 > 0.4
  const auto targets = toAxisTargets(cmd, k, 2.0);
  ASSERT_EQ(targets.size(), 3u);
  const AxisTarget& waist = targets[0].second;
  EXPECT_DOUBLE_EQ(targetPosition(waist, t[1], 3.0), 0.4);
  const AxisTarget& elbow = targets[1].second;
  EXPECT_TRUE(elbow.has_position);
  EXPECT_DOUBLE_EQ(targetPosition(elbow, t[3], 2.0), 1.2);
  EXPECT_DOUBLE_EQ(targetPosition(elbow, t[3], 3.0), 0.7);  // moves at -0.5 rad/s
  EXPECT_DOUBLE_EQ(targetPosition(elbow, t[3], 10.0), 0.0);  // ... down to the lower limit

  // Position motor with the gains, keeping the URDF damping (friction replaced).
  const JointMotor passive = passiveMotor(def.joints[1], 0);
  EXPECT_TRUE(passive.enabled);
  EXPECT_DOUBLE_EQ(passive.max_torque, 2.0);
  EXPECT_DOUBLE_EQ(passive.hertz, 0.0);
  const JointMotor m = targetMotor(elbow, t[3], MotorGains{60.0, 0.7, 80.0}, passive, 2.5);
  EXPECT_TRUE(m.enabled);
  EXPECT_DOUBLE_EQ(m.target, 0.95);
  EXPECT_DOUBLE_EQ(m.hertz, 60.0);
  EXPECT_DOUBLE_EQ(m.damping_ratio, 0.7);
  EXPECT_DOUBLE_EQ(m.max_torque, 80.0);
  EXPECT_DOUBLE_EQ(m.damping, 0.5);
}

// Finite inputs can overflow on an unlimited axis; the core refuses the motor (jointMotorError),
// which is why the node drops such a target instead of handing it to World::setJointMotor.
TEST(TargetPose, OverflowOnAnUnlimitedAxisIsCaughtByTheCoreRule) {
  AxisInfo free_axis;
  free_axis.name = "wheel";
  AxisTarget t;
  t.active = t.has_position = true;
  t.position = 1e308;
  t.velocity = 1e308;
  const JointMotor m = targetMotor(t, free_axis, MotorGains{60.0, 1.0, 80.0}, JointMotor(), 10.0);
  EXPECT_FALSE(std::isfinite(m.target));
  EXPECT_NE(jointMotorError(m).find("target must be finite"), std::string::npos)
      << jointMotorError(m);
  free_axis.limited = true, free_axis.upper = 1.0;
  EXPECT_EQ(jointMotorError(targetMotor(t, free_axis, MotorGains{60.0, 1.0, 80.0}, JointMotor(),
                                        10.0)),
            "");  // a limited axis clamps it
}

TEST(TargetPose, VelocityOnlyMakesAVelocityMotor) {
  const RagdollDef def = model();
  const AxisTable t(def);
  const TargetPoseCommand cmd{{"waist_z"}, {}, {1.5}};
  const TargetPoseCheck k = checkTargetPose(cmd, t);
  ASSERT_TRUE(k.ok) << k.error;
  const AxisTarget target = toAxisTargets(cmd, k, 0.0)[0].second;
  EXPECT_FALSE(target.has_position);
  const JointMotor m = targetMotor(target, t[2], MotorGains{60.0, 1.0, 80.0},
                                   passiveMotor(def.joints[0], 2), 1.0);
  EXPECT_TRUE(m.enabled);
  EXPECT_DOUBLE_EQ(m.hertz, 0.0);
  EXPECT_DOUBLE_EQ(m.target_velocity, 1.5);
  EXPECT_DOUBLE_EQ(m.max_torque, 80.0);
  EXPECT_DOUBLE_EQ(m.damping, 0.3);
}
