// World-level closed-form checks: resting contact, bounce height, impulse/momentum, joints.
#include <gtest/gtest.h>

#include <cmath>

#include "joint_angles.hpp"
#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1e-3;
}  // namespace

TEST(World, BoxComesToRestOnGround) {
  World w;
  addGround(w);
  const Vec3 half(0.2, 0.15, 0.1);
  const BodyId box = addBox(w, half, 5.0, Vec3(0, 0, 0.6));
  for (int i = 0; i < 3000; ++i) w.step(kDt);
  const BodyState s = w.bodyState(box);
  const double bottom = s.pose.p.z() - half.z();
  EXPECT_GT(bottom, -0.005) << "penetration " << -bottom;
  EXPECT_LT(bottom, 0.001);
  EXPECT_LT(s.linear_velocity.norm(), 1e-3);
  EXPECT_LT(s.angular_velocity.norm(), 1e-2);
}

class Bounce : public ::testing::TestWithParam<double> {};

TEST_P(Bounce, ApexIsRestitutionSquaredTimesDropHeight) {
  const double e = GetParam();
  const double r = 0.1, drop = 1.0;
  World w;
  Material m;
  m.restitution = e;
  addGround(w, m);
  const BodyId ball = addSphere(w, r, 1.0, Vec3(0, 0, drop + r), m);
  bool bounced = false;
  double apex = 0.0;
  for (int i = 0; i < 3000; ++i) {
    w.step(kDt);
    const BodyState s = w.bodyState(ball);
    if (!bounced && s.linear_velocity.z() > 0.0) bounced = true;
    if (bounced) {
      apex = std::max(apex, s.com_position.z() - r);
      if (s.linear_velocity.z() < 0.0) break;
    }
  }
  ASSERT_TRUE(bounced);
  EXPECT_NEAR(apex, e * e * drop, 0.02 * e * e * drop) << "e=" << e;
  std::printf("[ bounce   ] e %.1f: apex %.4f m (closed form %.4f)\n", e, apex, e * e * drop);
}
INSTANTIATE_TEST_SUITE_P(Restitution, Bounce, ::testing::Values(0.2, 0.5, 0.8));

TEST(World, ImpulseAtCentreChangesMomentumByJ) {
  WorldDef def;
  def.gravity.setZero();
  World w(def);
  const BodyId b = addBox(w, Vec3(0.1, 0.2, 0.3), 3.0, Vec3(1, 2, 3));
  const Vec3 J(0.3, -1.7, 2.9);
  const Vec3 p0 = w.linearMomentum();
  w.applyLinearImpulse(b, J, w.comPosition(b));
  const Vec3 dp = w.linearMomentum() - p0;
  EXPECT_LT((dp - J).norm(), 1e-9 * J.norm());
  EXPECT_LT(w.angularMomentum(w.comPosition(b)).norm(), 1e-12);
}

TEST(World, OffCentreImpulseChangesAngularMomentumByRCrossJ) {
  WorldDef def;
  def.gravity.setZero();
  World w(def);
  const BodyId b = addBox(w, Vec3(0.1, 0.2, 0.3), 3.0, Vec3(1, 2, 3));
  w.setBodyState(b, Transform(Vec3(1, 2, 3), quatFromRpy(0.3, -0.2, 1.1)), Vec3::Zero(),
                 Vec3::Zero());
  const Vec3 J(0.3, -1.7, 2.9), point = w.comPosition(b) + Vec3(0.05, -0.1, 0.2);
  const Vec3 origin(0.5, -0.5, 0.25);
  const Vec3 L0 = w.angularMomentum(origin);
  w.applyLinearImpulse(b, J, point);
  const Vec3 dL = w.angularMomentum(origin) - L0;
  const Vec3 expected = (point - origin).cross(J);
  EXPECT_LT((dL - expected).norm(), 1e-9 * expected.norm());
  EXPECT_LT((w.linearMomentum() - J).norm(), 1e-9 * J.norm());
  // Free flight afterwards conserves both (gyroscopic term included).
  for (int i = 0; i < 2000; ++i) w.step(kDt);
  EXPECT_LT((w.linearMomentum() - J).norm(), 1e-9 * J.norm());
  EXPECT_LT((w.angularMomentum(origin + J / 3.0 * w.time()) - expected).norm(), 1e-3 * expected.norm());
}

TEST(World, ForceForDurationAddsImpulse) {
  WorldDef def;
  def.gravity.setZero();
  World w(def);
  const BodyId b = addBox(w, Vec3(0.1, 0.1, 0.1), 2.0, Vec3::Zero());
  for (int i = 0; i < 500; ++i) {
    w.applyForce(b, Vec3(10, 0, 0), w.comPosition(b));
    w.step(kDt);
  }
  EXPECT_NEAR(w.linearMomentum().x(), 5.0, 1e-9);
}

// Compound pendulum on a hinge: small-angle period 2 pi sqrt(I_pivot / (m g d)).
TEST(World, HingePendulumPeriod) {
  World w;
  BodyDef anchor_def;
  anchor_def.type = BodyType::Static;
  const BodyId anchor = w.createBody(anchor_def);
  const double m = 2.0, d = 0.5, half = 0.05;
  BodyDef bob_def;
  bob_def.mass = m;
  bob_def.pose.p = Vec3(0, 0, 2.0);
  bob_def.com = Vec3(0, 0, -d);
  const double Ic = 2.0 / 5.0 * m * half * half;
  bob_def.inertia = Mat3::Identity() * Ic;
  const BodyId bob = w.createBody(bob_def);
  HingeJointDef hj;
  hj.body_a = anchor;
  hj.body_b = bob;
  hj.frame_a.p = Vec3(0, 0, 2.0);
  hj.axis = Vec3::UnitY();
  const JointId j = w.createHingeJoint(hj);
  const double theta0 = 0.05;
  w.setBodyState(bob, Transform(Vec3(0, 0, 2.0), Quat(Eigen::AngleAxisd(theta0, Vec3::UnitY()))),
                 Vec3::Zero(), Vec3::Zero());
  const double T = oscillationPeriod(w, kDt, 10000, [&] { return w.hingeAngle(j); });
  ASSERT_GT(T, 0.0);
  const double expected = 2 * M_PI * std::sqrt((Ic + m * d * d) / (m * 9.81 * d));
  EXPECT_NEAR(T, expected, 0.005 * expected);
  EXPECT_LT(w.jointAnchorError(j).norm(), 1e-4);
}

TEST(World, HingeLimitHolds) {
  World w;
  BodyDef anchor_def;
  anchor_def.type = BodyType::Static;
  const BodyId anchor = w.createBody(anchor_def);
  BodyDef bob_def;
  bob_def.mass = 1.0;
  bob_def.com = Vec3(0.3, 0, 0);
  bob_def.inertia = Mat3::Identity() * 0.01;
  const BodyId bob = w.createBody(bob_def);
  HingeJointDef hj;
  hj.body_a = anchor;
  hj.body_b = bob;
  hj.axis = Vec3::UnitY();  // gravity pulls the horizontal arm down: positive angle about +y
  hj.enable_limit = true;
  hj.lower = -0.2;
  hj.upper = 0.4;
  const JointId j = w.createHingeJoint(hj);
  double max_angle = -1;
  for (int i = 0; i < 2000; ++i) {
    w.step(kDt);
    max_angle = std::max(max_angle, w.hingeAngle(j));
  }
  EXPECT_LT(max_angle, 0.4 + 0.01);
  EXPECT_NEAR(w.hingeAngle(j), 0.4, 0.01);
}

namespace {
// An arm (1 kg, COM 0.3 m out) on a static anchor through a ball joint with Euler limits
// (y-x-z, as a URDF chain), started spinning at `spin`; steps it and returns the worst excess
// of an angle over its range.
struct LimitedArm {
  World w;
  BallJointDef bj;
  JointId joint;
  LimitedArm(const WorldDef& wd, const Vec3& spin) : w(wd) {
    BodyDef anchor_def;
    anchor_def.type = BodyType::Static;
    BodyDef arm;
    arm.mass = 1.0;
    arm.com = Vec3(0.3, 0.0, 0.0);
    arm.inertia = Mat3::Identity() * 0.01;
    arm.angular_velocity = spin;
    bj.body_a = w.createBody(anchor_def);
    bj.body_b = w.createBody(arm);
    bj.axes = {Vec3::UnitY(), Vec3::UnitX(), Vec3::UnitZ()};
    bj.enable_limits = true;
    bj.lower = {-0.5, -0.3, -0.4};
    bj.upper = {0.6, 0.3, 0.2};
    joint = w.createBallJoint(bj);
  }
  double stepWorstExcess(int steps) {
    double worst = 0.0;
    for (int i = 0; i < steps; ++i) {
      w.step(kDt);
      const auto t = w.ballAngles(joint);
      for (int k = 0; k < 3; ++k)
        worst = std::max({worst, bj.lower[k] - t[k], t[k] - bj.upper[k]});
    }
    return worst;
  }
};
}  // namespace

TEST(World, BallJointEulerLimitsHold) {
  LimitedArm arm(WorldDef(), Vec3(3.0, -2.0, 4.0));
  EXPECT_LT(arm.stepWorstExcess(3000), 0.02);
  EXPECT_LT(arm.w.jointAnchorError(arm.joint).norm(), 1e-4);
}

// Spun fast, the arm crosses most of a range within one step (up to 0.2 rad per 1 ms step):
// the limits still catch it within the substep that reaches them. Substeps after the first
// keep the advanced angles of joints whose limits are open (joint.cpp, limitsOpen); this checks
// that a joint turning into a limit within the step is not left on stale angles and rows, and
// that a limit whose two rows are skipped together (part_angle_limit.hpp) is not skipped when
// the arm would cross it within the substep.
TEST(World, BallJointEulerLimitsHoldWhenSpunFast) {
  WorldDef wd;
  wd.sleep.enabled = false;
  // Each spin and its reverse: every axis runs into its lower and its upper limit first.
  for (const Vec3& spin : {Vec3(40.0, -30.0, 50.0), Vec3(-120.0, 80.0, 100.0),
                           Vec3(0.0, 150.0, -60.0), Vec3(-40.0, 30.0, -50.0),
                           Vec3(120.0, -80.0, -100.0), Vec3(0.0, -150.0, 60.0)}) {
    LimitedArm arm(wd, spin);
    const double worst = arm.stepWorstExcess(1000);
    EXPECT_LT(worst, 2e-3) << "spin " << spin.transpose();  // the speculative rows stop it
    EXPECT_LT(arm.w.jointAnchorError(arm.joint).norm(), 1e-3) << "spin " << spin.transpose();
    std::printf("[ limits   ] spin (%g, %g, %g) rad/s: worst excess %.4f rad\n", spin.x(),
                spin.y(), spin.z(), worst);
  }
}

// The Euler decomposition reproduces the rotation, and its Jacobian rows match finite differences.
TEST(JointAngles, EulerRoundTripAndRates) {
  const std::array<Vec3, 3> axes = {Vec3::UnitY(), Vec3::UnitX(), Vec3::UnitZ()};  // det -1
  const EulerBasis basis(axes);
  const Quat fa = quatFromRpy(0.2, -0.4, 1.0);
  const Vec3 t(0.3, -0.7, 1.2);
  auto rot = [&](const Vec3& a) {
    return Quat(Eigen::AngleAxisd(a[0], axes[0]) * Eigen::AngleAxisd(a[1], axes[1]) *
                Eigen::AngleAxisd(a[2], axes[2]));
  };
  const Quat fb = fa * rot(t);
  EXPECT_LT((basis.angles(fa, fb) - t).norm(), 1e-12);
  std::array<Vec3, 3> rows;
  Vec3 t_rows;
  ASSERT_TRUE(basis.angles(fa, fb, t_rows, &rows));
  EXPECT_LT((t_rows - t).norm(), 1e-12);
  const Vec3 wrel(0.3, -0.2, 0.5);  // world relative angular velocity of B
  const double eps = 1e-7;
  const Quat fb2 = (Quat(Eigen::AngleAxisd(eps * wrel.norm(), wrel.normalized())) * fb).normalized();
  const Vec3 rate = (basis.angles(fa, fb2) - t) / eps;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(rows[i].dot(wrel), rate[i], 1e-5);
}
