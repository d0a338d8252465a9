// Hinge joint: pendulum period, limit held.
#include <gtest/gtest.h>

#include <cmath>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1e-3;
}  // namespace

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
