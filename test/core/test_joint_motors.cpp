// Joint motors: velocity and position targets, the torque cap, viscous damping; each in double
// (lanes 1) and in the anchor's float lane (lanes 4 and 8, point_row_lanes.inc).
#include <gtest/gtest.h>

#include <cmath>

#include "joint_test_util.hpp"
#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
struct Arm {
  World w;
  BodyId bar;
  JointId hinge;
  explicit Arm(const WorldDef& def, const JointMotor& motor) : w(def) {
    const BodyId anchor = addAnchor(w);
    BodyDef d;
    d.mass = 1.0;
    d.com = Vec3(0.5, 0, 0);
    d.inertia = Mat3::Identity() * 0.02;
    bar = w.createBody(d);
    HingeJointDef h;
    h.body_a = anchor;
    h.body_b = bar;
    h.axis = Vec3::UnitY();
    h.motor = motor;
    hinge = w.createHingeJoint(h);
  }
};

WorldDef withLanes(WorldDef d, int lanes) {
  d.solver.lanes = lanes;
  return d;
}

constexpr int kLaneWidths[] = {1, 4, 8};
}  // namespace

TEST(JointMotor, VelocityTargetReached) {
  JointMotor m;
  m.enabled = true;
  m.target_velocity = 2.0;
  m.max_torque = 50.0;
  for (const int lanes : kLaneWidths) {
    Arm arm(withLanes(zeroG(), lanes), m);
    for (int i = 0; i < 200; ++i) arm.w.step(kDt);
    EXPECT_NEAR(arm.w.bodyState(arm.bar).angular_velocity.y(), 2.0, 1e-5) << "lanes " << lanes;
  }
}

TEST(JointMotor, PositionTargetHeldAgainstGravity) {
  JointMotor m;
  m.enabled = true;
  m.target = 0.5;
  m.hertz = 10.0;
  m.damping_ratio = 1.0;
  m.max_torque = 100.0;
  for (const int lanes : kLaneWidths) {
    Arm arm(withLanes(WorldDef(), lanes), m);
    for (int i = 0; i < 3000; ++i) arm.w.step(kDt);
    // gravity torque m g d cos(theta) ~ 4.3 N m; the drive's stiffness is I_com w^2 (the
    // frequency is relative to the body's own rotational inertia, as in Box2D), so it sags by
    // tau / (I_com w^2) ~ 0.05 rad
    const double I = 0.02, w2 = std::pow(2 * M_PI * 10, 2);
    const double theta = arm.w.hingeAngle(arm.hinge);
    EXPECT_NEAR(theta, 0.5 + 9.81 * 0.5 * std::cos(theta) / (I * w2), 2e-3) << "lanes " << lanes;
  }
}

TEST(JointMotor, TorqueCapLimitsTheDrive) {
  JointMotor m;
  m.enabled = true;
  m.target = 0.0;
  m.hertz = 10.0;
  m.max_torque = 2.0;  // less than m g d = 4.9 N m: the arm falls
  for (const int lanes : kLaneWidths) {
    Arm arm(withLanes(WorldDef(), lanes), m);
    double max_angle = 0.0;
    for (int i = 0; i < 2000; ++i) {
      arm.w.step(kDt);
      max_angle = std::max(max_angle, arm.w.hingeAngle(arm.hinge));
    }
    EXPECT_GT(max_angle, 1.5) << "lanes " << lanes;  // past the balance acos(2 / 4.9) = 1.15 rad
    // the drive pushes back with its whole cap while the arm is past the target
    double e[3];
    ASSERT_EQ(arm.w.jointAxisEfforts(arm.hinge, e), 1);
    EXPECT_LE(std::abs(e[0]), 2.0 * (1.0 + 1e-6)) << "lanes " << lanes;
  }
}

TEST(JointMotor, DampingDecaysSwing) {
  JointMotor m;
  m.damping = 0.5;  // N m s/rad
  for (const int lanes : kLaneWidths) {
    Arm arm(withLanes(zeroG(), lanes), m);
    arm.w.setBodyState(arm.bar, Transform(), Vec3(0, 0, -2.0), Vec3(0, 4.0, 0));  // about the pivot
    for (int i = 0; i < 1000; ++i) arm.w.step(kDt);
    // I w' = -c w  ->  w(t) = w0 exp(-c t / I), I about the pivot = 0.27
    EXPECT_NEAR(arm.w.bodyState(arm.bar).angular_velocity.y(), 4.0 * std::exp(-0.5 / 0.27), 0.02)
        << "lanes " << lanes;
  }
}

// A position motor holds a level bar (the joint's limit keeps its rows active); turned off, it
// lets go: the bar falls under gravity instead of being held by the motor's last impulse.
TEST(JointMotor, TurnedOffMotorLetsGo) {
  JointMotor hold;
  hold.enabled = true;
  hold.hertz = 30.0;
  hold.max_torque = 1e4;
  for (const int lanes : kLaneWidths)
  for (const JointType type : {JointType::Hinge, JointType::Ball, JointType::Prismatic}) {
    World w(withLanes(noSleep(), lanes));
    const BodyId anchor = addAnchor(w);
    BodyDef d;
    d.mass = 2.0;
    d.com = Vec3(0.5, 0, 0);
    d.inertia = Mat3::Identity() * 0.04;
    const BodyId bar = w.createBody(d);
    JointId j;
    int axis = 0;
    if (type == JointType::Hinge) {
      HingeJointDef h;
      h.body_a = anchor;
      h.body_b = bar;
      h.axis = Vec3::UnitY();
      h.enable_limit = true;
      h.lower = -2.0;
      h.upper = 2.0;
      h.motor = hold;
      j = w.createHingeJoint(h);
    } else if (type == JointType::Ball) {
      BallJointDef b;
      b.body_a = anchor;
      b.body_b = bar;
      b.motors = {hold, hold, hold};
      j = w.createBallJoint(b);
      axis = 1;  // y: the one gravity turns
    } else {
      PrismaticJointDef p;
      p.body_a = anchor;
      p.body_b = bar;
      p.axis = Vec3::UnitZ();
      p.enable_limit = true;
      p.lower = -2.0;
      p.upper = 2.0;
      p.motor = hold;
      j = w.createPrismaticJoint(p);
    }
    for (int i = 0; i < 500; ++i) w.step(kDt);
    const Vec3 held = w.comPosition(bar);
    w.setJointMotor(j, axis, JointMotor());
    for (int i = 0; i < 300; ++i) w.step(kDt);
    // Free fall drops the COM by ~0.44 m in 0.3 s; a pendulum turning about y by ~0.3 m.
    EXPECT_LT(w.comPosition(bar).z(), held.z() - 0.2) << int(type) << " lanes " << lanes;
  }
}
