// Joint springs (period, breaking), motors (velocity, position, torque cap) and damping.
#include <gtest/gtest.h>

#include <cmath>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1e-3;

BodyId addAnchor(World& w) {
  BodyDef d;
  d.type = BodyType::Static;
  return w.createBody(d);
}

BodyId addBall(World& w, double mass, const Vec3& pos) {
  BodyDef d;
  d.pose.p = pos;
  d.mass = mass;
  d.inertia = Mat3::Identity() * 0.01 * mass;
  return w.createBody(d);
}
}  // namespace

// A mass on a Hooke spring oscillates with period 2 pi sqrt(m / k).
TEST(JointSpring, PeriodMatchesClosedForm) {
  WorldDef def;
  def.gravity.setZero();
  World w(def);
  const double m = 2.0, k = 800.0;
  const BodyId anchor = addAnchor(w), ball = addBall(w, m, Vec3(0.05, 0, 0));
  BallJointDef j;
  j.body_a = anchor;
  j.body_b = ball;
  j.spring.stiffness = k;
  w.createBallJoint(j);
  const double T = oscillationPeriod(w, kDt, 3000, [&] { return w.comPosition(ball).x(); });
  ASSERT_GT(T, 0.0);
  const double expected = 2 * M_PI * std::sqrt(m / k);
  EXPECT_NEAR(T, expected, 0.01 * expected);
  std::printf("[ spring   ] period %.5f s (closed form %.5f)\n", T, expected);
}

// Pulled with a slowly rising force, the spring joint breaks at the step where its force first
// passes the limit; afterwards the body flies on with its momentum and the event is reported once.
TEST(JointSpring, BreaksWhenForcePassesLimit) {
  WorldDef def;
  def.gravity.setZero();
  World w(def);
  const BodyId anchor = addAnchor(w), ball = addBall(w, 1.0, Vec3::Zero());
  BallJointDef j;
  j.body_a = anchor;
  j.body_b = ball;
  j.spring = {2000.0, 60.0, 50.0};
  const JointId id = w.createBallJoint(j);
  double last_force = 0.0;
  int broke_at = -1;
  for (int i = 0; i < 5000 && broke_at < 0; ++i) {
    w.applyForce(ball, Vec3(20.0 * w.time(), 0, 0), w.comPosition(ball));
    w.step(kDt);
    if (w.isJointBroken(id)) broke_at = i;
    else last_force = w.jointForce(id);
  }
  ASSERT_GE(broke_at, 0) << "never broke";
  EXPECT_LE(last_force, 50.0);
  EXPECT_GT(w.jointForce(id), 50.0);
  EXPECT_NEAR(w.jointForce(id), 50.0, 0.5);  // the force rises ~0.02 N per step
  const auto events = w.takeBrokenJoints();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].index, id.index);
  EXPECT_TRUE(w.takeBrokenJoints().empty());
  const Vec3 p = w.linearMomentum();
  for (int i = 0; i < 100; ++i) w.step(kDt);
  EXPECT_LT((w.linearMomentum() - p).norm(), 1e-12);  // free: no force from the broken joint
  std::printf("[ break    ] broke at t = %.3f s with %.3f N (limit 50 N; step before %.3f N)\n",
              (broke_at + 1) * kDt, w.jointForce(id), last_force);
}

// A rigid joint with a break force lets a limb fly off under a hard hit.
TEST(JointSpring, RigidJointBreaksUnderImpulse) {
  WorldDef def;
  def.gravity.setZero();
  World w(def);
  const BodyId a = addBall(w, 5.0, Vec3::Zero()), b = addBall(w, 1.0, Vec3(0.3, 0, 0));
  BallJointDef j;
  j.body_a = a;
  j.body_b = b;
  j.frame_a.p = Vec3(0.15, 0, 0);
  j.frame_b.p = Vec3(-0.15, 0, 0);
  j.spring.break_force = 2000.0;
  const JointId id = w.createBallJoint(j);
  // 0.3 N s: the joint passes 5/6 of it to the 5 kg body within one 1/3 ms substep (750 N),
  // and both then move at 0.05 m/s
  w.applyLinearImpulse(b, Vec3(0.3, 0, 0), w.comPosition(b));
  w.step(kDt);
  EXPECT_FALSE(w.isJointBroken(id));
  EXPECT_NEAR(w.bodyState(a).linear_velocity.x(), 0.05, 1e-6);
  EXPECT_NEAR(w.bodyState(b).linear_velocity.x(), 0.05, 1e-6);
  w.applyLinearImpulse(b, Vec3(30.0, 0, 0), w.comPosition(b));
  for (int i = 0; i < 10; ++i) w.step(kDt);
  EXPECT_TRUE(w.isJointBroken(id));
  // it transmitted at most 2000 N for one substep (0.67 N s) before breaking
  EXPECT_GT(w.bodyState(b).linear_velocity.x(), 29.0);
  EXPECT_NEAR(w.linearMomentum().x(), 30.3, 1e-9);
}

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
WorldDef zeroG() {
  WorldDef d;
  d.gravity.setZero();
  return d;
}
}  // namespace

TEST(JointMotor, VelocityTargetReached) {
  JointMotor m;
  m.enabled = true;
  m.target_velocity = 2.0;
  m.max_torque = 50.0;
  Arm arm(zeroG(), m);
  for (int i = 0; i < 200; ++i) arm.w.step(kDt);
  EXPECT_NEAR(arm.w.bodyState(arm.bar).angular_velocity.y(), 2.0, 1e-5);
}

TEST(JointMotor, PositionTargetHeldAgainstGravity) {
  JointMotor m;
  m.enabled = true;
  m.target = 0.5;
  m.hertz = 10.0;
  m.damping_ratio = 1.0;
  m.max_torque = 100.0;
  Arm arm(WorldDef(), m);
  for (int i = 0; i < 3000; ++i) arm.w.step(kDt);
  // gravity torque m g d cos(theta) ~ 4.3 N m; the drive's stiffness is I_com w^2 (the
  // frequency is relative to the body's own rotational inertia, as in Box2D), so it sags by
  // tau / (I_com w^2) ~ 0.05 rad
  const double I = 0.02, w2 = std::pow(2 * M_PI * 10, 2);
  const double theta = arm.w.hingeAngle(arm.hinge);
  EXPECT_NEAR(theta, 0.5 + 9.81 * 0.5 * std::cos(theta) / (I * w2), 2e-3);
}

TEST(JointMotor, TorqueCapLimitsTheDrive) {
  JointMotor m;
  m.enabled = true;
  m.target = 0.0;
  m.hertz = 10.0;
  m.max_torque = 2.0;  // less than m g d = 4.9 N m: the arm falls
  Arm arm(WorldDef(), m);
  double max_angle = 0.0;
  for (int i = 0; i < 2000; ++i) {
    arm.w.step(kDt);
    max_angle = std::max(max_angle, arm.w.hingeAngle(arm.hinge));
  }
  EXPECT_GT(max_angle, 1.5);  // swings past the static balance acos(2 / 4.9) = 1.15 rad
}

TEST(JointMotor, DampingDecaysSwing) {
  JointMotor m;
  m.damping = 0.5;  // N m s/rad
  Arm arm(zeroG(), m);
  arm.w.setBodyState(arm.bar, Transform(), Vec3(0, 0, -2.0), Vec3(0, 4.0, 0));  // about the pivot
  for (int i = 0; i < 1000; ++i) arm.w.step(kDt);
  // I w' = -c w  ->  w(t) = w0 exp(-c t / I), I about the pivot = 0.27
  EXPECT_NEAR(arm.w.bodyState(arm.bar).angular_velocity.y(), 4.0 * std::exp(-0.5 / 0.27), 0.02);
}
