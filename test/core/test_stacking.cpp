// Multi-body contact cases: sphere collisions, stacks, a pyramid, a heavy box on a light one,
// warm starting across a new time step (sleeping: test_sleep.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1e-3;
}  // namespace

// Head-on collision of two spheres: momentum conserved, separating speed = e * closing speed.
class SphereCollision : public ::testing::TestWithParam<double> {};
TEST_P(SphereCollision, ConservesMomentumAndRestitution) {
  const double e = GetParam();
  WorldDef def;
  def.gravity.setZero();
  World w(def);
  Material m;
  m.restitution = e;
  auto sphere = [&](double mass, double r, const Vec3& p, const Vec3& v) {
    BodyDef d;
    d.pose.p = p;
    d.mass = mass;
    d.inertia = Mat3::Identity() * 0.4 * mass * r * r;
    d.linear_velocity = v;
    const BodyId b = w.createBody(d);
    w.addShape(b, {Geometry::sphere(r), Transform(), m});
    return b;
  };
  const BodyId a = sphere(2.0, 0.1, Vec3(-0.5, 0, 0), Vec3(3, 0, 0));
  const BodyId b = sphere(1.0, 0.15, Vec3(0.5, 0, 0), Vec3(-2, 0, 0));
  const Vec3 p0 = w.linearMomentum();
  const double closing = 5.0;
  for (int i = 0; i < 400; ++i) w.step(kDt);
  const double va = w.bodyState(a).linear_velocity.x(), vb = w.bodyState(b).linear_velocity.x();
  EXPECT_LT((w.linearMomentum() - p0).norm(), 1e-9 * p0.norm());
  EXPECT_NEAR(vb - va, e * closing, 0.01 * e * closing);
  std::printf("[ spheres  ] e %.1f: separating %.4f m/s (closed form %.4f), |dp| %.1e\n", e, vb - va,
              e * closing, (w.linearMomentum() - p0).norm());
}
INSTANTIATE_TEST_SUITE_P(Restitution, SphereCollision, ::testing::Values(0.2, 0.5, 0.8, 1.0));

TEST(Stacking, TenBoxesStayStackedTenSeconds) {
  World w;
  addGround(w);
  const Vec3 half(0.25, 0.25, 0.25);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 10; ++i) boxes.push_back(addBox(w, half, 1.0, Vec3(0, 0, 0.25 + 0.5 * i)));
  for (int i = 0; i < 10000; ++i) w.step(kDt);
  double drift = 0.0;
  for (int i = 0; i < 10; ++i) {
    const Vec3 p = w.comPosition(boxes[i]);
    drift = std::max(drift, std::hypot(p.x(), p.y()));
    EXPECT_NEAR(p.z(), 0.25 + 0.5 * i, 0.01) << "box " << i;
  }
  EXPECT_LT(drift, 0.01);
  std::printf("[ stack    ] 10 boxes after 10 s: horizontal drift %.2e m, top z %.4f (built 4.75)\n", drift,
              w.comPosition(boxes.back()).z());
}

TEST(Stacking, TwentyBoxPyramidStaysUp) {
  World w;
  addGround(w);
  const Vec3 half(0.25, 0.25, 0.25);
  std::vector<std::pair<BodyId, Vec3>> boxes;
  // rows of 6, 5, 4, 3, 2 = 20 boxes
  int row = 0;
  for (int n = 6; n >= 2; --n, ++row)
    for (int i = 0; i < n; ++i) {
      const Vec3 p((i - 0.5 * (n - 1)) * 0.51, 0, 0.25 + 0.5 * row);
      boxes.emplace_back(addBox(w, half, 1.0, p), p);
    }
  ASSERT_EQ(boxes.size(), 20u);
  for (int i = 0; i < 5000; ++i) w.step(kDt);
  double worst = 0.0;
  for (const auto& [b, p0] : boxes) worst = std::max(worst, (w.comPosition(b) - p0).norm());
  EXPECT_LT(worst, 0.02);
  std::printf("[ pyramid  ] 20 boxes after 5 s: max displacement %.4f m\n", worst);
}

TEST(Stacking, HeavyBoxOnLightBoxDoesNotSink) {
  World w;
  addGround(w);
  const Vec3 half(0.2, 0.2, 0.1);
  const BodyId light = addBox(w, half, 1.0, Vec3(0, 0, 0.1));
  const BodyId heavy = addBox(w, half, 100.0, Vec3(0, 0, 0.3));
  double sink = 0.0;
  for (int i = 0; i < 3000; ++i) {
    w.step(kDt);
    const double gap_bottom = w.comPosition(light).z() - half.z();
    const double gap_top = (w.comPosition(heavy).z() - half.z()) - (w.comPosition(light).z() + half.z());
    sink = std::max({sink, -gap_bottom, -gap_top});
  }
  EXPECT_LT(sink, 0.005);
  std::printf("[ ratio    ] 100 kg on 1 kg: max penetration %.4f m\n", sink);
}

// Warm starting across a change of time step (the node's physics_rate at run time): a stack
// of five boxes resting at dt = 1 ms goes on at 4 ms. The impulses kept from the last step
// are per substep and are scaled by the new substep over the old (warmStartScale), so the
// first 4 ms step starts from the load the stack already carries: its top box drops 8.6 um
// in it, its fastest box moves at 5.0e-3 m/s. Taken as they were, the first substep holds a
// quarter of the load: 55 um and 1.2e-2 m/s.
TEST(Stacking, WarmStartCarriesTheLoadToANewTimeStep) {
  WorldDef def;
  def.sleep.enabled = false;  // neither asleep nor on the rest substeps when dt changes
  World w(def);
  addGround(w);
  const Vec3 half(0.2, 0.2, 0.1);
  std::vector<BodyId> boxes;
  for (int k = 0; k < 5; ++k) boxes.push_back(addBox(w, half, 2.0, Vec3(0, 0, 0.1 + 0.2 * k)));
  for (int i = 0; i < 500; ++i) w.step(kDt);
  const double z0 = w.comPosition(boxes.back()).z();
  w.step(4 * kDt);
  const double drop = z0 - w.comPosition(boxes.back()).z();
  double fastest = 0.0;
  for (const BodyId b : boxes) fastest = std::max(fastest, w.bodyState(b).linear_velocity.norm());
  EXPECT_LT(drop, 2e-5);
  EXPECT_LT(fastest, 8e-3);
  std::printf("[ stack    ] 1 ms -> 4 ms: top box dropped %.2e m, fastest box %.2e m/s\n", drop,
              fastest);
}

// A world whose bodies all sleep steps without colliding or solving (World::Impl::settled), and
// sleeping and static bodies keep last step's boxes (aabb_kept): what the world is told between
// steps must still reach it.

// Overlapping bodies are separated by impulses, so the correction splits by inverse mass
// (the light box moves 3x as far as the 3x heavier one), momentum stays zero, and the relax
// sweeps take the push-out velocity back: no kinetic energy is added.
TEST(Penetration, CorrectionSplitsByInverseMassWithoutEnergy) {
  WorldDef def;
  def.gravity.setZero();
  World w(def);
  const Vec3 half(0.1, 0.1, 0.1);
  const BodyId light = addBox(w, half, 1.0, Vec3(-0.09, 0, 0));
  const BodyId heavy = addBox(w, half, 3.0, Vec3(0.09, 0, 0));  // 2 cm overlap
  double max_ke = 0.0;
  for (int i = 0; i < 20; ++i) {
    w.step(kDt);
    max_ke = std::max(max_ke, w.kineticEnergy());
  }
  const double dl = -0.09 - w.comPosition(light).x(), dh = w.comPosition(heavy).x() - 0.09;
  EXPECT_NEAR(dl / dh, 3.0, 0.03);
  EXPECT_LT(w.linearMomentum().norm(), 1e-12);
  EXPECT_LT(max_ke, 1e-6);
  std::printf("[ split    ] moved light %.4f m, heavy %.4f m (ratio %.3f), max KE %.1e J\n", dl, dh,
              dl / dh, max_ke);
}

// World::setSleep changes the sleep settings in place: two stacked boxes asleep stay asleep
// (same poses, same contacts) when the thresholds change; sleep off wakes them and keeps them
// awake; sleep on again puts them to sleep time_to_sleep after the switch at the earliest (the
// slow times restart, even those counted before sleep went off); a bad value throws and changes
// nothing.

