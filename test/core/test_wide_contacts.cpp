// The contact rows in float lanes (SolverSettings::lanes 4 and 8, contact_wide.hpp): the same
// bits at both widths and on any thread count, and the closed forms of resting, sliding,
// incline and bounce cases still hold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ragdoll_sim/ragdoll.hpp"
#include "ragdoll_sim/state_hash.hpp"
#include "ragdoll_sim/world.hpp"
#include "ragdoll_sim/world_reports.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1e-3;
constexpr double kG = 9.81;

WorldDef wideDef(int lanes, int threads = 1) {
  WorldDef def;
  def.gravity = Vec3(0, 0, -kG);
  def.solver.lanes = lanes;
  def.threads = threads;
  def.sleep.enabled = false;
  return def;
}

Material friction(double mu_s, double mu_k, double e = 0.0) {
  Material m;
  m.static_friction = mu_s;
  m.kinetic_friction = mu_k;
  m.restitution = e;
  return m;
}

// Three layers of 4 x 4 boxes, each a little turned and offset, dropped on the ground: many
// manifolds that share bodies, so several colours and full blocks.
void boxPile(World& w) {
  addGround(w, friction(0.6, 0.5));
  const Vec3 half(0.1, 0.1, 0.1);
  for (int layer = 0; layer < 3; ++layer)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const double a = 0.05 * ((i * 7 + j * 3 + layer) % 5);
        const Transform pose(Vec3(0.21 * i + 0.01 * layer, 0.21 * j, 0.1 + 0.205 * layer + 0.02),
                             Quat(Eigen::AngleAxisd(a, Vec3::UnitZ())));
        addBody(w, Geometry::box(half), 1.0 + 0.1 * i, boxInertia(half, 1.0 + 0.1 * i), pose,
                friction(0.6, 0.5));
      }
}

// Five boxes in a limb of ball joints, dropped tilted on the ground.
void ragdollDrop(World& w) {
  addGround(w, friction(0.8, 0.6));
  RagdollDef d;
  for (int i = 0; i < 5; ++i) {
    LinkDef l;
    l.name = "link" + std::to_string(i);
    l.mass = i == 0 ? 10.0 : 2.0;
    l.inertia = l.mass * Vec3(0.002, 0.01, 0.01).asDiagonal();
    l.rest_pose = Transform(Vec3(0.3 * i, 0.02 * i * i, 0), Quat::Identity());
    ShapeDef sh;
    sh.geometry = Geometry::box(Vec3(0.12, 0.05, 0.05));
    l.shapes.push_back(sh);
    d.links.push_back(l);
  }
  for (int i = 0; i < 4; ++i) {
    RagdollJointDef j;
    j.name = "j" + std::to_string(i);
    j.kind = RagdollJointKind::Ball;
    j.parent = i;
    j.child = i + 1;
    j.frame_parent = Transform(Vec3(0.15, 0, 0), Quat::Identity());
    j.frame_child = Transform(Vec3(-0.15, 0, 0), Quat::Identity());
    d.joints.push_back(j);
  }
  const Quat tilt(Eigen::AngleAxisd(0.3, Vec3(1, 1, 0).normalized()));
  spawnRagdoll(w, d, Transform(Vec3(0, 0, 0.4), tilt));
}

template <class Build>
uint64_t hashAfter(Build&& build, int lanes, int threads, int steps) {
  World w(wideDef(lanes, threads));
  build(w);
  uint64_t h = kFnvOffsetBasis;
  for (int i = 0; i < steps; ++i) {
    w.step(kDt);
    h = hashStates(w, h);
  }
  return h;
}

template <class Build>
void expectSameBits(Build&& build, const char* name) {
  const uint64_t scalar = hashAfter(build, 1, 1, 600);
  const uint64_t w4 = hashAfter(build, 4, 1, 600);
  std::printf("[ wide contacts ] %s: lanes 1 %016llx, lanes 4 %016llx\n", name,
              (unsigned long long)scalar, (unsigned long long)w4);
  EXPECT_NE(w4, scalar) << name << ": the float path did not run";
  for (int lanes : {4, 8})
    for (int threads : {1, 2})
      EXPECT_EQ(hashAfter(build, lanes, threads, 600), w4)
          << name << " lanes " << lanes << " threads " << threads;
}

// The contact force on `body` from the ground (body B side or A side), summed over reports.
double groundForceZ(const World& w, BodyId body) {
  std::vector<ContactReport> reports;
  w.contactReports(reports);
  double fz = 0.0;
  for (const ContactReport& r : reports) {
    if (r.body_b == body) fz += r.force_b.z();
    if (r.body_a == body) fz += r.force_a.z();
  }
  return fz;
}

class WideContacts : public ::testing::TestWithParam<int> {};
}  // namespace

TEST(WideContactsBits, BoxPileSameAtBothWidthsAndThreadCounts) {
  expectSameBits(boxPile, "box pile");
}
TEST(WideContactsBits, RagdollDropSameAtBothWidthsAndThreadCounts) {
  expectSameBits(ragdollDrop, "ragdoll drop");
}

// A box at rest: its contact impulses over the substep carry its weight.
TEST_P(WideContacts, RestingBoxCarriesItsWeight) {
  World w(wideDef(GetParam()));
  addGround(w, friction(0.6, 0.5));
  const double m = 3.0;
  const BodyId box = addBox(w, Vec3(0.2, 0.15, 0.1), m, Vec3(0, 0, 0.1), friction(0.6, 0.5));
  for (int i = 0; i < 1000; ++i) w.step(kDt);
  const double fz = groundForceZ(w, box);
  EXPECT_NEAR(fz, m * kG, 1e-4 * m * kG) << "lanes " << GetParam();
  std::printf("[ wide contacts ] lanes %d: resting box force %.6f N (m g %.6f)\n", GetParam(), fz,
              m * kG);
}

// A box sliding on flat ground decelerates at mu_k g.
TEST_P(WideContacts, SlidingBoxDeceleratesAtMuG) {
  const double mu_k = 0.4, v0 = 3.0;
  World w(wideDef(GetParam()));
  addGround(w, friction(mu_k + 0.1, mu_k));
  const Vec3 half(0.2, 0.2, 0.1);
  const BodyId box = addBody(w, Geometry::box(half), 4.0, boxInertia(half, 4.0),
                             Transform(Vec3(0, 0, half.z()), Quat::Identity()),
                             friction(mu_k + 0.1, mu_k), Vec3(v0, 0, 0));
  for (int i = 0; i < 100; ++i) w.step(kDt);
  const double v1 = w.bodyState(box).linear_velocity.x();
  for (int i = 0; i < 300; ++i) w.step(kDt);
  const double v2 = w.bodyState(box).linear_velocity.x();
  const double a = (v1 - v2) / (300 * kDt);
  EXPECT_NEAR(a, mu_k * kG, 0.01 * mu_k * kG) << "lanes " << GetParam();
  std::printf("[ wide contacts ] lanes %d: sliding deceleration %.5f (mu g %.5f)\n", GetParam(), a,
              mu_k * kG);
}

// A box on an incline slides with g (sin - mu_k cos) above atan(mu_s) and holds below it.
TEST_P(WideContacts, InclineSlidesAboveAndHoldsBelowFrictionAngle) {
  const double mu_s = 0.6, mu_k = 0.5, critical = std::atan(mu_s);
  for (double theta : {critical - 0.05, critical + 0.1}) {
    World w(wideDef(GetParam()));
    const Material m = friction(mu_s, mu_k);
    const Quat slope(Eigen::AngleAxisd(theta, Vec3::UnitY()));
    addGround(w, m, slope);
    const Vec3 half(0.1, 0.1, 0.05);
    const BodyId box = addBody(w, Geometry::box(half), 2.0, boxInertia(half, 2.0),
                               Transform(slope * Vec3(0, 0, half.z()), slope), m);
    // down the slope: gravity's part in the plane
    const Vec3 g(0, 0, -kG), n = slope * Vec3::UnitZ();
    const Vec3 along = (g - g.dot(n) * n).normalized();
    const Vec3 p0 = w.comPosition(box);
    for (int i = 0; i < 200; ++i) w.step(kDt);
    const double s1 = w.pointVelocity(box, w.comPosition(box)).dot(along);
    for (int i = 0; i < 300; ++i) w.step(kDt);
    const double s2 = w.pointVelocity(box, w.comPosition(box)).dot(along);
    const double moved = (w.comPosition(box) - p0).dot(along);
    if (theta < critical) {
      EXPECT_LT(std::abs(moved), 1e-3) << "lanes " << GetParam() << " theta " << theta;
      std::printf("[ wide contacts ] lanes %d: incline %.4f below %.4f: moved %.2e m\n",
                  GetParam(), theta, critical, moved);
    } else {
      const double a = (s2 - s1) / (300 * kDt);
      const double expected = kG * (std::sin(theta) - mu_k * std::cos(theta));
      EXPECT_NEAR(a, expected, 0.01 * expected) << "lanes " << GetParam();
      std::printf("[ wide contacts ] lanes %d: incline %.4f above %.4f: a %.5f (closed form "
                  "%.5f)\n", GetParam(), theta, critical, a, expected);
    }
  }
}

// A sphere dropped from h with restitution e bounces back to e^2 h.
TEST_P(WideContacts, SphereBouncesToESquaredH) {
  const double e = 0.7, r = 0.1, h = 1.0;
  World w(wideDef(GetParam()));
  addGround(w, friction(0.5, 0.5, e));
  const BodyId ball = addSphere(w, r, 1.0, Vec3(0, 0, r + h), friction(0.5, 0.5, e));
  bool bounced = false;
  double peak = 0.0;
  for (int i = 0; i < 1500; ++i) {
    w.step(kDt);
    const double z = w.comPosition(ball).z() - r, vz = w.bodyState(ball).linear_velocity.z();
    if (vz > 0.0) bounced = true;
    if (bounced) peak = std::max(peak, z);
  }
  EXPECT_NEAR(peak, e * e * h, 0.03 * e * e * h) << "lanes " << GetParam();
  std::printf("[ wide contacts ] lanes %d: bounce %.4f m (e^2 h %.4f)\n", GetParam(), peak,
              e * e * h);
}

// Boxes colliding off centre without gravity keep their linear momentum to double rounding:
// the lanes' impulses reach both bodies of a contact through their double inverse masses.
TEST_P(WideContacts, CollidingBoxesKeepLinearMomentum) {
  WorldDef def = wideDef(GetParam());
  def.gravity.setZero();
  World w(def);
  const Vec3 half(0.1, 0.08, 0.06);
  for (int i = 0; i < 4; ++i) {
    const double m = 1.0 + 0.7 * i;
    const Transform pose(Vec3(0.3 * i, 0.03 * i, 0.02 * (i % 2)),
                         Quat(Eigen::AngleAxisd(0.3 * i, Vec3(1, 2, 3).normalized())));
    addBody(w, Geometry::box(half), m, boxInertia(half, m), pose, friction(0.6, 0.5, 0.3),
            Vec3(i % 2 ? -1.5 : 2.0, 0.1 * i, -0.2 * (i % 2)));
  }
  const Vec3 p0 = w.linearMomentum();
  for (int i = 0; i < 500; ++i) w.step(kDt);
  const double dp = (w.linearMomentum() - p0).norm() / p0.norm();
  EXPECT_LT(dp, 1e-12) << "lanes " << GetParam();
  std::printf("[ wide contacts ] lanes %d: relative change of the linear momentum %.2e\n",
              GetParam(), dp);
}

// Ten stacked boxes (coloured red-black: every other contact in one colour) sleep with no
// contact deeper than the linear slop, on the full count and on the rest substeps: solved in
// one colour order in every biased sweep, every other contact sank to the slop.
TEST_P(WideContacts, TenBoxStackRestsWithinTheSlop) {
  for (const bool rest : {false, true}) {
    WorldDef def;
    def.solver.lanes = GetParam();
    if (!rest) def.sleep.rest_substeps = 0;
    World w(def);
    addGround(w);
    const Vec3 half(0.25, 0.25, 0.25);
    std::vector<BodyId> boxes;
    for (int i = 0; i < 10; ++i) boxes.push_back(addBox(w, half, 1.0, Vec3(0, 0, 0.25 + 0.5 * i)));
    int i = 0;
    for (; i < 3000 && (i == 0 || w.awakeBodyCount() > 0); ++i) w.step(kDt);
    ASSERT_EQ(w.awakeBodyCount(), 0);
    double deepest = 0.0, below = 0.0;
    for (const BodyId b : boxes) {
      deepest = std::max(deepest, below - (w.comPosition(b).z() - half.z()));
      below = w.comPosition(b).z() + half.z();
    }
    EXPECT_LT(deepest, def.solver.linear_slop) << "lanes " << GetParam() << " rest " << rest;
    std::printf("[ wide contacts ] lanes %d: 10-box stack %s asleep after %d steps, deepest "
                "contact %.3e m\n", GetParam(), rest ? "rest substeps" : "full count", i, deepest);
  }
}

INSTANTIATE_TEST_SUITE_P(Lanes, WideContacts, ::testing::Values(4, 8));
