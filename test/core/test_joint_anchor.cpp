// The joint anchor: Hooke spring period, breaking force, and the point part's effective mass.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "joint_test_util.hpp"
#include "part_point.hpp"
#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

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

// The point part's effective mass, formed entry by entry (part_point.hpp), equals the textbook
// J M^-1 J^T = (1/mA + 1/mB) I - skew(rA) IA^-1 skew(rA) - skew(rB) IB^-1 skew(rB), and a
// singular K (two immovable bodies) gives a zero inverse rather than inf.
TEST(PointPart, EffectiveMassMatchesProductForm) {
  std::srand(7);
  const auto spd = [] {
    const Mat3 R = Quat(Eigen::Vector4d(Eigen::Vector4d::Random()).normalized()).toRotationMatrix();
    const Vec3 d = Vec3(Vec3::Random()).cwiseAbs() + Vec3::Constant(0.1);  // Random() is lazy
    return Mat3(R * d.asDiagonal() * R.transpose());
  };
  for (int trial = 0; trial < 20; ++trial) {
    SolverBody A, B;
    A.inv_mass = 0.5 + trial;
    B.inv_mass = trial % 3 == 0 ? 0.0 : 2.0;
    A.inv_inertia = spd();
    B.inv_inertia = trial % 3 == 0 ? Mat3::Zero() : spd();
    const Vec3 rA = Vec3::Random(), rB = 0.3 * Vec3::Random();
    const Mat3 expected = (A.inv_mass + B.inv_mass + 0.25) * Mat3::Identity() -
                          skew(rA) * A.inv_inertia * skew(rA) - skew(rB) * B.inv_inertia * skew(rB);
    const Mat3 K = pointMass(A, B, rA, rB, 0.25);
    EXPECT_LT((K - expected).norm(), 1e-12 * expected.norm()) << "trial " << trial;
    EXPECT_LT((inverseOrZero(K) * expected - Mat3::Identity()).norm(), 1e-9) << "trial " << trial;
  }
  const Mat3 K0 = pointMass(SolverBody(), SolverBody(), Vec3(1, 2, 3), Vec3::Zero(), 0.0);
  EXPECT_TRUE(inverseOrZero(K0).isZero(0.0));
}
