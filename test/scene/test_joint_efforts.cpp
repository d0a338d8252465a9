// Joint effort commands (JointEffortCommand), the Scene's axis efforts and loads: a commanded
// effort against closed forms (tau / I about the axis, forces on a slider), equal and opposite,
// its duration, the checks, and the loads on a ragdoll at rest.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ragdoll_sim/scene.hpp"
#include "scene_recorder.hpp"
#include "scene_views.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {

constexpr double kArmMass = 2.0, kArmCom = 0.4;  // kg; m from the joint to the arm's COM
constexpr double kIcom = 0.03;                    // kg m^2 about the arm's COM (y and z)
constexpr double kG = 9.81;

// base -(joint)- arm, the joint at the base's origin, the arm's COM kArmCom along x. Hinge
// "shoulder" about y; ball "sh_z", "sh_y", "sh_x" (axes z, y, x); prismatic "slide" along x.
RagdollDef armModel(RagdollJointKind kind) {
  RagdollDef def;
  def.name = "arm";
  LinkDef base;
  base.name = "base";
  base.mass = 3.0;
  base.inertia = Mat3::Identity() * 0.05;
  LinkDef arm;
  arm.name = "arm";
  arm.mass = kArmMass;
  arm.com = Vec3(kArmCom, 0, 0);
  arm.inertia = Vec3(0.01, kIcom, kIcom).asDiagonal();
  def.links = {base, arm};
  RagdollJointDef j;
  j.kind = kind;
  j.parent = 0;
  j.child = 1;
  if (kind == RagdollJointKind::Ball) {
    j.name = "sh_z+sh_y+sh_x";
    j.axes = {Vec3::UnitZ(), Vec3::UnitY(), Vec3::UnitX()};
    j.source_joints = {"sh_z", "sh_y", "sh_x"};
  } else if (kind == RagdollJointKind::Prismatic) {
    j.name = "slide";
    j.axes = {Vec3::UnitX()};
    j.source_joints = {"slide"};
  } else {
    j.name = "shoulder";
    j.axes = {Vec3::UnitY()};
    j.source_joints = {"shoulder"};
  }
  def.joints = {j};
  return def;
}

struct ArmScene {
  Recorder rec;
  std::unique_ptr<Scene> scene;
  // arm_yaw: the arm spawns turned about z (a ball's first Euler angle).
  ArmScene(RagdollJointKind kind, bool fixed_base, bool gravity = false, double arm_yaw = 0.0) {
    SceneDef sd;
    if (!gravity) sd.world.gravity = Vec3::Zero();
    sd.ground = false;
    scene = std::make_unique<Scene>(sd, &rec);
    SpawnDef sp;
    sp.name = "r";
    sp.def = armModel(kind);
    sp.def.links[1].rest_pose.q = Quat(Eigen::AngleAxisd(arm_yaw, Vec3::UnitZ()));
    sp.pose = Transform(Vec3(0, 0, 1), Quat::Identity());
    sp.fixed_base = fixed_base;
    std::string error;
    EXPECT_EQ(scene->addRagdoll(sp, &error), SpawnResult::Added) << error;
    EXPECT_TRUE(scene->start(&error)) << error;
  }
  bool command(std::vector<std::string> names, std::vector<double> efforts,
               double duration = -1.0) {
    JointEffortCommand c;
    c.names = std::move(names);
    c.efforts = std::move(efforts);
    c.duration = duration;
    return scene->submit("r", c, scene->timeNs());
  }
  void run(int steps) {
    for (int i = 0; i < steps; ++i) scene->step();
  }
  BodyState arm() const { return scene->world().bodyState(scene->bodies(0).bodies[1]); }
  BodyState base() const { return scene->world().bodyState(scene->bodies(0).bodies[0]); }
  double effort(int axis) const {
    std::vector<double> e;
    scene->jointEfforts(0, e);
    return e.at(static_cast<size_t>(axis));
  }
};

const double kIhinge = kIcom + kArmMass * kArmCom * kArmCom;  // parallel-axis theorem

}  // namespace

// A torque tau about the hinge of a pinned base turns the arm at alpha = tau / I.
TEST(JointEffort, HingeAcceleratesAtTauOverI) {
  ArmScene s(RagdollJointKind::Hinge, /*fixed_base=*/true);
  const double tau = 1.4, alpha = tau / kIhinge;
  ASSERT_TRUE(s.command({"shoulder"}, {tau}));
  s.run(100);
  EXPECT_NEAR(s.arm().angular_velocity.y(), alpha * 0.1, 0.01 * alpha * 0.1);
  EXPECT_EQ(s.scene->activeEffortCount(), 1u);
  EXPECT_NEAR(s.effort(0), tau, 1e-9);  // nothing else acts on the axis
  EXPECT_EQ(s.scene->counters().applied, 1u);
}

// On a ball joint the effort turns about that Euler axis of the chain: sh_y's at yaw t0 is
// Rz(t0) y.
TEST(JointEffort, BallAxisAcceleratesAtTauOverI) {
  const double t0 = 0.5;
  ArmScene s(RagdollJointKind::Ball, /*fixed_base=*/true, /*gravity=*/false, t0);
  EXPECT_NEAR(s.scene->world().ballAngles(s.scene->bodies(0).joints[0])[0], t0, 1e-9);
  const double tau = -0.7, alpha = tau / kIhinge;
  ASSERT_TRUE(s.command({"sh_y"}, {tau}));
  s.run(100);
  const Vec3 w = s.arm().angular_velocity;
  const Vec3 axis(-std::sin(t0), std::cos(t0), 0.0);
  EXPECT_NEAR(w.dot(axis), alpha * 0.1, 0.01 * std::abs(alpha) * 0.1);
  EXPECT_NEAR((w - w.dot(axis) * axis).norm(), 0.0, 1e-3 * std::abs(alpha) * 0.1);
  std::vector<double> e;
  s.scene->jointEfforts(0, e);
  ASSERT_EQ(e.size(), 3u);
  EXPECT_NEAR(e[1], tau, 1e-9);
}

// A force along a prismatic axis accelerates the slider at f / m.
TEST(JointEffort, PrismaticForceAcceleratesAtFOverM) {
  ArmScene s(RagdollJointKind::Prismatic, /*fixed_base=*/true);
  const double f = 5.0;
  ASSERT_TRUE(s.command({"slide"}, {f}));
  s.run(100);
  EXPECT_NEAR(s.arm().linear_velocity.x(), f / kArmMass * 0.1, 0.01 * f / kArmMass * 0.1);
  EXPECT_NEAR(s.arm().angular_velocity.norm(), 0.0, 1e-6);
}

// Free in space, the pair of torques changes neither momentum nor angular momentum, and turns
// the two links apart.
TEST(JointEffort, EqualAndOppositeOnAFreePair) {
  ArmScene s(RagdollJointKind::Hinge, /*fixed_base=*/false);
  const World& w = s.scene->world();
  const Vec3 com0 = w.comPosition(s.scene->bodies(0).bodies[0]);
  ASSERT_TRUE(s.command({"shoulder"}, {2.0}));
  s.run(200);
  EXPECT_GT(s.arm().angular_velocity.y(), 1.0);
  EXPECT_LT(s.base().angular_velocity.y(), -0.5);
  // One torque alone would have given tau t = 0.4 N m s.
  EXPECT_NEAR(w.angularMomentum(com0).norm(), 0.0, 1e-6);
  EXPECT_NEAR(w.linearMomentum().norm(), 0.0, 1e-6);
}

// A duration counts down: 0.05 s accelerates for 50 steps, 0 for one; a later command
// replaces the axis's effort; clearForces ends the rest.
TEST(JointEffort, DurationEndsItAndLaterCommandsReplace) {
  ArmScene s(RagdollJointKind::Hinge, /*fixed_base=*/true);
  const double tau = 1.4, alpha = tau / kIhinge, dt = s.scene->dt();
  ASSERT_TRUE(s.command({"shoulder"}, {tau}, 0.05));
  s.run(50);
  EXPECT_EQ(s.scene->activeEffortCount(), 0u);
  EXPECT_NEAR(s.effort(0), tau, 1e-9);  // it acted in the last step
  s.run(50);
  EXPECT_NEAR(s.effort(0), 0.0, 1e-9);
  const double w1 = s.arm().angular_velocity.y();
  EXPECT_NEAR(w1, alpha * 0.05, 0.01 * alpha * 0.05);

  ASSERT_TRUE(s.command({"shoulder"}, {tau}, 0.0));
  s.run(5);
  EXPECT_NEAR(s.arm().angular_velocity.y() - w1, alpha * dt, 0.01 * alpha * dt);

  ASSERT_TRUE(s.command({"shoulder"}, {tau}));
  ASSERT_TRUE(s.command({"shoulder"}, {-tau}));  // replaces it
  s.run(10);
  EXPECT_EQ(s.scene->activeEffortCount(), 1u);
  EXPECT_NEAR(s.effort(0), -tau, 1e-9);
  EXPECT_EQ(s.scene->clearForces(), 1u);
  EXPECT_EQ(s.scene->activeEffortCount(), 0u);
  s.run(1);
  EXPECT_NEAR(s.effort(0), 0.0, 1e-9);
}

// Each bad command is rejected whole with a WARN naming the problem; the sim goes on and a
// good command still acts.
TEST(JointEffort, BadCommandsAreRejectedWithAWarn) {
  ArmScene s(RagdollJointKind::Hinge, /*fixed_base=*/true);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Bad {
    std::vector<std::string> names;
    std::vector<double> efforts;
    double duration;
    const char* kind;
    const char* text;
  };
  const Bad bad[] = {
      {{"elbow"}, {1.0}, -1.0, "joint effort/unknown joint", "'elbow'"},
      {{"shoulder"}, {nan}, -1.0, "joint effort/effort not finite", "nan"},
      {{"shoulder"}, {2e5}, -1.0, "joint effort/above max_torque", "max_torque = 100000"},
      {{"shoulder"}, {1.0, 2.0}, -1.0, "joint effort/efforts length", "1 names but 2 efforts"},
      {{"shoulder", "shoulder"}, {1.0, 1.0}, -1.0, "joint effort/repeated joint", "twice"},
      {{"shoulder"}, {1.0}, nan, "joint effort/duration not finite", "not finite"},
      {{}, {}, -1.0, "joint effort/no names", "no joint names"},
  };
  for (const Bad& b : bad) {
    s.rec.messages.clear();
    ASSERT_TRUE(s.command(b.names, b.efforts, b.duration));
    s.run(1);
    const SceneMessage* m = s.rec.find(b.kind);
    ASSERT_NE(m, nullptr) << b.kind;
    EXPECT_EQ(m->level, SceneMessage::Level::Warn);
    EXPECT_NE(m->text.find(b.text), std::string::npos) << m->text;
  }
  EXPECT_EQ(s.scene->counters().rejected, std::size(bad));
  EXPECT_EQ(s.scene->activeEffortCount(), 0u);
  EXPECT_NEAR(s.arm().angular_velocity.norm(), 0.0, 1e-9);
  // A good one next to a bad one is rejected with it.
  ASSERT_TRUE(s.command({"shoulder", "elbow"}, {1.0, 1.0}));
  s.run(1);
  EXPECT_EQ(s.scene->activeEffortCount(), 0u);
  ASSERT_TRUE(s.command({"shoulder"}, {1.0}));
  s.run(10);
  EXPECT_GT(s.arm().angular_velocity.y(), 0.0);
  EXPECT_EQ(s.scene->counters().applied, 1u);
}

// The prismatic axis is capped by max_force, not max_torque.
TEST(JointEffort, PrismaticCapIsMaxForce) {
  ArmScene s(RagdollJointKind::Prismatic, /*fixed_base=*/true);
  SceneDef sd;
  ASSERT_TRUE(s.command({"slide"}, {sd.limits.max_force * 1.5}));
  s.run(1);
  EXPECT_TRUE(s.rec.saw("joint effort/above max_force"));
}

// A target pose holds the arm level against gravity: the effort is the motor's torque on the
// arm about +y, -m g d, and stays so when a commanded effort helps (the motor gives the rest);
// the joint's wrench on the arm (the child) carries its weight.
TEST(JointEffort, HeldArmReportsMotorPlusCommand) {
  ArmScene s(RagdollJointKind::Hinge, /*fixed_base=*/true, /*gravity=*/true);
  TargetPoseCommand hold;
  hold.names = {"shoulder"};
  hold.position = {0.0};
  ASSERT_TRUE(s.scene->submit("r", hold, s.scene->timeNs()));
  s.run(500);
  const double mgd = kArmMass * kG * kArmCom;
  EXPECT_NEAR(s.effort(0), -mgd, 0.01 * mgd);
  std::vector<LinkLoad> links;
  std::vector<JointLoad> joints;
  s.scene->loads(0, links, joints);
  ASSERT_EQ(links.size(), 2u);
  ASSERT_EQ(joints.size(), 1u);
  EXPECT_EQ(joints[0].axes, 1);
  EXPECT_NEAR(joints[0].effort[0], -mgd, 0.01 * mgd);
  EXPECT_NEAR(joints[0].wrench.force.z(), kArmMass * kG, 5e-3 * kArmMass * kG);
  EXPECT_NEAR(joints[0].wrench.torque.y(), -mgd, 0.01 * mgd);
  ASSERT_TRUE(s.command({"shoulder"}, {-3.0}));
  s.run(300);
  EXPECT_NEAR(s.effort(0), -mgd, 0.01 * mgd);
}

// At rest on the ground the links' contact forces add up to the weight.
TEST(JointEffort, LoadsAtRestCarryTheWeight) {
  Recorder rec;
  SceneDef sd;
  Scene scene(sd, &rec);
  SpawnDef sp;
  sp.name = "r";
  sp.def = stickModel();
  sp.pose = Transform(Vec3(0, 0, 0.1), Quat::Identity());
  std::string error;
  ASSERT_EQ(scene.addRagdoll(sp, &error), SpawnResult::Added) << error;
  ASSERT_TRUE(scene.start(&error)) << error;
  for (int i = 0; i < 1500; ++i) scene.step();
  std::vector<LinkLoad> links;
  std::vector<JointLoad> joints;
  scene.loads(0, links, joints);
  Vec3 sum = Vec3::Zero();
  for (const LinkLoad& l : links) sum += l.contact_force;
  const double weight = sp.def.totalMass() * 9.81;
  EXPECT_NEAR(sum.z(), weight, 5e-3 * weight);
  EXPECT_NEAR(sum.head<2>().norm(), 0.0, 5e-3 * weight);
}
