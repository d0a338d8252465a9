// Joint wrenches and axis efforts (World::jointWrench, World::jointAxisEfforts) against closed
// forms: a motor holding a horizontal pendulum, a hanging chain, external torque pairs against
// a brake and viscous damping, a prismatic motor holding a weight, a ball joint's Euler axes.
#include <gtest/gtest.h>

#include <cmath>

#include "joint_test_util.hpp"
#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {

constexpr double kMass = 2.0, kArm = 0.5;  // pendulum: kg, m from the joint to the COM

JointMotor holdAt(double target, double max_torque = 1e4) {
  JointMotor m;
  m.enabled = true;
  m.target = target;
  m.hertz = 30.0;
  m.damping_ratio = 1.0;
  m.max_torque = max_torque;
  return m;
}

// A bar on a static pivot at the origin, its COM kArm along the link's x.
struct Pendulum {
  World w;
  BodyId pivot, bar;
  JointId joint;
  explicit Pendulum(const WorldDef& def = WorldDef(), const Quat& q = Quat::Identity())
      : w(def) {
    pivot = addStatic(w);
    bar = addDynamic(w, kMass, diag(0.01, 0.04, 0.04), Transform(Vec3::Zero(), q),
                     Vec3(kArm, 0, 0));
  }
  void run(double seconds) {
    for (int i = 0; i < int(seconds / kDt); ++i) w.step(kDt);
  }
  double effort(int axis = 0) const {
    double e[3];
    w.jointAxisEfforts(joint, e);
    return e[axis];
  }
};

}  // namespace

// The motor holds the bar level against gravity's torque (0, m g l, 0) about the pivot: it
// applies -m g l about +y, and the anchor carries the weight.
TEST(JointReports, HingeMotorHoldsHorizontalPendulum) {
  Pendulum p;
  HingeJointDef h;
  h.body_a = p.pivot;
  h.body_b = p.bar;
  h.axis = Vec3::UnitY();
  h.motor = holdAt(0.0);
  p.joint = p.w.createHingeJoint(h);
  p.run(2.0);
  const double mgl = kMass * kG * kArm;
  const double theta = p.w.hingeAngle(p.joint);
  EXPECT_LT(std::abs(theta), 0.02);
  double e[3] = {7, 7, 7};
  ASSERT_EQ(p.w.jointAxisEfforts(p.joint, e), 1);
  EXPECT_NEAR(e[0], -mgl, 0.01 * mgl);
  EXPECT_NEAR(e[0], -mgl * std::cos(theta), 2e-3 * mgl);
  const JointWrench jw = p.w.jointWrench(p.joint);
  EXPECT_NEAR(jw.force.z(), kMass * kG, 5e-3 * kMass * kG);
  EXPECT_NEAR(jw.force.x(), 0.0, 5e-3 * kMass * kG);
  EXPECT_NEAR(jw.torque.y(), -mgl * std::cos(theta), 0.01 * mgl);
  EXPECT_NEAR(jw.torque.x(), 0.0, 0.01 * mgl);
  EXPECT_NEAR(jw.torque.z(), 0.0, 0.01 * mgl);
}

// Mirrored: about -y the same motor lifts the bar with +m g l.
TEST(JointReports, HingeEffortSignFollowsTheAxis) {
  Pendulum p;
  HingeJointDef h;
  h.body_a = p.pivot;
  h.body_b = p.bar;
  h.axis = -Vec3::UnitY();
  h.motor = holdAt(0.0);
  p.joint = p.w.createHingeJoint(h);
  p.run(1.0);
  const double mgl = kMass * kG * kArm;
  EXPECT_NEAR(p.effort(), mgl, 0.01 * mgl);
}

// Four links hang from a static pivot by hinges: joint k carries the weight below it.
TEST(JointReports, HangingChainCarriesTheWeightBelow) {
  World w(noSleep());
  const BodyId top = addStatic(w);
  const double masses[4] = {1.0, 2.5, 0.7, 3.0}, len = 0.3;
  std::vector<JointId> joints;
  BodyId parent = top;
  for (int k = 0; k < 4; ++k) {
    // Link k hangs from z = -k len, its COM half a link below its origin.
    const BodyId link = addDynamic(w, masses[k], diag(0.02, 0.02, 0.005),
                                   Transform(Vec3(0, 0, -k * len), Quat::Identity()),
                                   Vec3(0, 0, -0.5 * len));
    HingeJointDef h;
    h.body_a = parent;
    h.body_b = link;
    h.frame_a = local(w, parent, Transform(Vec3(0, 0, -k * len), Quat::Identity()));
    h.axis = k % 2 ? Vec3::UnitX() : Vec3::UnitY();
    joints.push_back(w.createHingeJoint(h));
    parent = link;
  }
  for (int i = 0; i < 1000; ++i) w.step(kDt);
  for (int k = 0; k < 4; ++k) {
    double below = 0.0;
    for (int i = k; i < 4; ++i) below += masses[i] * kG;
    const JointWrench jw = w.jointWrench(joints[size_t(k)]);
    EXPECT_NEAR(jw.force.z(), below, 5e-3 * below) << "joint " << k;
    EXPECT_NEAR(jw.force.head<2>().norm(), 0.0, 5e-3 * below) << "joint " << k;
    EXPECT_NEAR(jw.torque.norm(), 0.0, 1e-3 * below) << "joint " << k;
    EXPECT_NEAR(w.jointForce(joints[size_t(k)]), jw.force.norm(), 1e-9 * below);
  }
}

// A spring anchor reports its spring force: the weight of the mass it holds.
TEST(JointReports, SpringAnchorReportsItsForce) {
  World w(noSleep());
  const BodyId top = addStatic(w);
  const BodyId bob = addDynamic(w, 3.0, diag(0.01, 0.01, 0.01), Transform());
  BallJointDef b;
  b.body_a = top;
  b.body_b = bob;
  b.spring.stiffness = 2000.0;
  b.spring.damping = 50.0;
  const JointId j = w.createBallJoint(b);
  for (int i = 0; i < 2000; ++i) w.step(kDt);
  EXPECT_NEAR(w.jointWrench(j).force.z(), 3.0 * kG, 5e-3 * 3.0 * kG);
}

// No gravity; a torque pair tau (on the bar, minus on a free hub) about the hinge axis. A
// velocity motor at 0 (a brake) holds the bar with -tau; viscous damping c alone lets it turn
// at tau / c and then reports -tau too.
TEST(JointReports, TorquePairAgainstBrakeAndDamping) {
  const double tau = 3.0;
  for (const bool brake : {true, false}) {
    World w(zeroG());
    const BodyId hub = addDynamic(w, 5.0, diag(0.3, 0.3, 0.3), Transform());
    const BodyId bar = addDynamic(w, 1.0, diag(0.05, 0.05, 0.02), Transform(), Vec3(0.3, 0, 0));
    HingeJointDef h;
    h.body_a = hub;
    h.body_b = bar;
    h.axis = Vec3::UnitZ();
    if (brake) {
      h.motor.enabled = true;
      h.motor.max_torque = 100.0;
    } else {
      h.motor.damping = 2.0;
    }
    const JointId j = w.createHingeJoint(h);
    for (int i = 0; i < 3000; ++i) {
      const Vec3 axis = w.bodyPose(hub).q * Vec3::UnitZ();
      w.applyTorque(bar, tau * axis);
      w.applyTorque(hub, -tau * axis);
      w.step(kDt);
    }
    double e[3];
    ASSERT_EQ(w.jointAxisEfforts(j, e), 1);
    EXPECT_NEAR(e[0], -tau, 0.01 * tau) << (brake ? "brake" : "damping");
    if (!brake) {
      const Vec3 axis = w.bodyPose(hub).q * Vec3::UnitZ();
      const double rate = axis.dot(w.bodyState(bar).angular_velocity -
                                   w.bodyState(hub).angular_velocity);
      EXPECT_NEAR(rate, tau / 2.0, 0.01 * tau / 2.0);
    }
  }
}

// A slider on a static rail tilted by 30 degrees from the vertical: the motor pushes the mass
// up along the axis with m g cos(30 deg), the line part holds the rest; the wrench on the mass
// is its weight, upwards. Vertical: the motor alone holds m g.
TEST(JointReports, PrismaticMotorHoldsAWeight) {
  for (const double tilt : {0.0, M_PI / 6}) {
    World w;
    const Quat q(Eigen::AngleAxisd(tilt, Vec3::UnitX()));
    const BodyId rail = addStatic(w, Transform(Vec3(0, 0, 1), q));
    const BodyId mass = addDynamic(w, 4.0, diag(0.02, 0.02, 0.02), Transform(Vec3(0, 0, 1), q));
    PrismaticJointDef p;
    p.body_a = rail;
    p.body_b = mass;
    p.axis = Vec3::UnitZ();
    p.motor = holdAt(0.0);
    const JointId j = w.createPrismaticJoint(p);
    for (int i = 0; i < 1500; ++i) w.step(kDt);
    const double mg = 4.0 * kG;
    double e[3];
    ASSERT_EQ(w.jointAxisEfforts(j, e), 1);
    EXPECT_NEAR(e[0], mg * std::cos(tilt), 0.01 * mg) << "tilt " << tilt;
    const JointWrench jw = w.jointWrench(j);
    EXPECT_NEAR((jw.force - Vec3(0, 0, mg)).norm(), 0.0, 5e-3 * mg) << "tilt " << tilt;
    EXPECT_NEAR(jw.torque.norm(), 0.0, 1e-3 * mg) << "tilt " << tilt;
  }
}

// A ball joint with axes (z, y, x) held at yaw t0 by its motors: the bar lies level along
// (cos t0, sin t0, 0). Chain axis 1 is Rz(t0) y, about which gravity pulls with m g l, so its
// effort is -m g l (as a hinge about that axis reports), and axes 0 (z) and 2 (the bar) carry
// none.
TEST(JointReports, BallEulerEffortsMatchTheHinge) {
  const double t0 = 0.6, mgl = kMass * kG * kArm;
  const Quat yaw(Eigen::AngleAxisd(t0, Vec3::UnitZ()));
  Pendulum ball(WorldDef(), yaw);
  BallJointDef b;
  b.body_a = ball.pivot;
  b.body_b = ball.bar;
  // Both frames are the link frames: the bar's yaw is the Euler angle t0 from the start.
  b.axes = {Vec3::UnitZ(), Vec3::UnitY(), Vec3::UnitX()};
  b.motors = {holdAt(t0), holdAt(0.0), holdAt(0.0)};
  ball.joint = ball.w.createBallJoint(b);
  ball.run(2.0);
  double e[3];
  ASSERT_EQ(ball.w.jointAxisEfforts(ball.joint, e), 3);
  EXPECT_NEAR(e[0], 0.0, 0.01 * mgl);
  EXPECT_NEAR(e[1], -mgl, 0.01 * mgl);
  EXPECT_NEAR(e[2], 0.0, 0.01 * mgl);

  Pendulum hinge(WorldDef(), yaw);
  HingeJointDef h;
  h.body_a = hinge.pivot;
  h.body_b = hinge.bar;
  h.frame_a = Transform(Vec3::Zero(), yaw);
  h.axis = Vec3::UnitY();
  h.motor = holdAt(0.0);
  hinge.joint = hinge.w.createHingeJoint(h);
  hinge.run(2.0);
  EXPECT_NEAR(e[1], hinge.effort(), 0.01 * mgl);
}

// A weld carries the weight and the couple of a level cantilever; it has no axes.
TEST(JointReports, FixedJointCarriesTheCantilever) {
  Pendulum p;
  FixedJointDef f;
  f.body_a = p.pivot;
  f.body_b = p.bar;
  p.joint = p.w.createFixedJoint(f);
  p.run(1.0);
  const double mgl = kMass * kG * kArm;
  double e[3] = {1, 1, 1};
  EXPECT_EQ(p.w.jointAxisEfforts(p.joint, e), 0);
  EXPECT_EQ(e[0], 0.0);
  const JointWrench jw = p.w.jointWrench(p.joint);
  EXPECT_NEAR(jw.force.z(), kMass * kG, 5e-3 * kMass * kG);
  EXPECT_NEAR(jw.torque.y(), -mgl, 5e-3 * mgl);
}

// A broken joint reports zero, and so does one that never stepped.
TEST(JointReports, BrokenAndUnsteppedJointsReportZero) {
  Pendulum p;
  HingeJointDef h;
  h.body_a = p.pivot;
  h.body_b = p.bar;
  h.axis = Vec3::UnitY();
  h.motor = holdAt(0.0);
  p.joint = p.w.createHingeJoint(h);
  EXPECT_EQ(p.w.jointWrench(p.joint).force.norm(), 0.0);
  p.run(0.2);
  EXPECT_GT(p.w.jointWrench(p.joint).force.norm(), 1.0);
  p.w.breakJoint(p.joint);
  double e[3] = {1, 1, 1};
  EXPECT_EQ(p.w.jointAxisEfforts(p.joint, e), 1);
  EXPECT_EQ(e[0], 0.0);
  EXPECT_EQ(p.w.jointWrench(p.joint).force.norm(), 0.0);
  EXPECT_THROW(p.w.jointWrench(JointId{99}), std::out_of_range);
}

// No gravity; a slider spins at w about its own axis, B's COM r off it: only the joint holds B
// on its circle, so the wrench on B is m w^2 r towards the axis, in the direction B is now.
TEST(JointReports, SpinningSliderHoldsItsMassOnTheCircle) {
  World w(zeroG());
  const double mb = 1.0, ma = 5.0, r = 0.2, spin = 10.0;
  const Vec3 omega(0, 0, spin);
  const Vec3 ca(-mb / ma * r, 0, 0), cb(r, 0, 0);  // COMs about the system's at the origin
  const BodyId a = addDynamic(w, ma, diag(0.5, 0.5, 0.5), Transform(), ca, omega.cross(ca), omega);
  const BodyId b = addDynamic(w, mb, diag(0.01, 0.01, 0.01), Transform(), cb, omega.cross(cb),
                              omega);
  PrismaticJointDef p;
  p.body_a = a;
  p.body_b = b;
  p.axis = Vec3::UnitZ();
  p.motor = holdAt(0.0);
  const JointId j = w.createPrismaticJoint(p);
  for (int i = 0; i < 300; ++i) w.step(kDt);
  const Vec3 xb = w.comPosition(b);
  const Vec3 expected = -mb * spin * spin * Vec3(xb.x(), xb.y(), 0.0);
  const JointWrench jw = w.jointWrench(j);
  EXPECT_NEAR((jw.force - expected).norm(), 0.0, 2e-3 * expected.norm());
}
