// World-level closed-form checks: resting contact, bounce height, impulse and momentum.
#include <gtest/gtest.h>

#include <cmath>

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
