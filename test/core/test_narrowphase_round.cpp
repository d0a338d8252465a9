// Narrowphase of round shapes: sphere, capsule and cylinder pairs against closed-form depths,
// normals and point counts, separated and speculative cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "narrowphase_test_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::narrowphase_test;

// ------------------------------------------------------------------- spheres and capsules

TEST(Narrowphase, SphereSphere) {
  const Geometry a = Geometry::sphere(0.3), b = Geometry::sphere(0.2);
  Manifold m = run(a, at(0, 0, 0), b, at(0.45, 0, 0));
  ASSERT_EQ(m.count, 1);
  expectNormal(m, Vec3::UnitX());
  EXPECT_NEAR(m.points[0].separation, -0.05, 1e-12);
  EXPECT_TRUE(m.points[0].point.isApprox(Vec3(0.275, 0, 0)));
  m = run(a, at(0, 0, 0), b, at(0, 0.52, 0), 0.05);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, 0.02, 1e-12);
  EXPECT_EQ(run(a, at(0, 0, 0), b, at(0, 0.52, 0), 0.01).count, 0);
  m = run(a, at(0, 0, 0), b, at(0, 0, 0));  // concentric: any unit normal, full depth
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.normal.norm(), 1, 1e-12);
  EXPECT_NEAR(m.points[0].separation, -0.5, 1e-12);
}

TEST(Narrowphase, SphereCapsule) {
  const Geometry s = Geometry::sphere(0.2), c = Geometry::capsule(0.1, 0.5);
  Manifold m = run(s, at(0.1, 0, 0.29), c, at(0, 0, 0, rot(kPi / 2, Vec3::UnitY())));  // side
  ASSERT_EQ(m.count, 1);
  expectNormal(m, -Vec3::UnitZ());
  EXPECT_NEAR(m.points[0].separation, -0.01, 1e-12);
  m = run(s, at(0.2, 0, 0), c, at(0, 0, 0, rot(kPi / 2, Vec3::UnitY())));  // centre on the axis
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.normal.norm(), 1, 1e-12);
  EXPECT_NEAR(std::abs(m.normal.x()), 0, 1e-12);
  EXPECT_NEAR(m.points[0].separation, -0.3, 1e-12);
  m = run(s, at(0.79, 0, 0), c, at(0, 0, 0, rot(kPi / 2, Vec3::UnitY())));  // end cap
  ASSERT_EQ(m.count, 1);
  expectNormal(m, -Vec3::UnitX());
  EXPECT_NEAR(m.points[0].separation, -0.01, 1e-12);
}

TEST(Narrowphase, CapsuleCapsuleParallelAndCrossed) {
  const Geometry c = Geometry::capsule(0.1, 0.5);
  const Quat alongx = rot(kPi / 2, Vec3::UnitY());
  Manifold m = run(c, at(0, 0, 0, alongx), c, at(0.3, 0, 0.19, alongx));
  ASSERT_EQ(m.count, 2);
  expectNormal(m, Vec3::UnitZ());
  expectAllSep(m, -0.01);
  const double x0 = std::min(m.points[0].point.x(), m.points[1].point.x());
  const double x1 = std::max(m.points[0].point.x(), m.points[1].point.x());
  EXPECT_NEAR(x0, -0.2, 1e-9);
  EXPECT_NEAR(x1, 0.5, 1e-9);
  // Ids stable under a tiny move.
  EXPECT_EQ(ids(m), ids(run(c, at(0, 0, 0, alongx), c, at(0.3001, 0.0001, 0.1899, alongx))));

  m = run(c, at(0, 0, 0, alongx), c, at(0.1, 0.1, 0.18, rot(kPi / 2, Vec3::UnitX())));
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.02, 1e-12);
  expectNormal(m, Vec3::UnitZ());
  EXPECT_EQ(run(c, at(0, 0, 0, alongx), c, at(0.1, 0.1, 0.3, alongx)).count, 0);
}

// --------------------------------------------------------------------------- cylinders

TEST(Narrowphase, SphereCylinder) {
  const Geometry s = Geometry::sphere(0.1), cyl = Geometry::cylinder(0.5, 1.0);
  Manifold m = run(s, at(0.59, 0, 0.3), cyl, Transform());  // side
  ASSERT_EQ(m.count, 1);
  expectNormal(m, -Vec3::UnitX());
  EXPECT_NEAR(m.points[0].separation, -0.01, 1e-12);
  m = run(s, at(0.2, 0.1, 1.09), cyl, Transform());  // cap
  ASSERT_EQ(m.count, 1);
  expectNormal(m, -Vec3::UnitZ());
  EXPECT_NEAR(m.points[0].separation, -0.01, 1e-12);
  m = run(s, at(0.6, 0, 1.1), cyl, Transform(), 0.1);  // rim
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, 0.1 * std::sqrt(2.0) - 0.1, 1e-12);
  m = run(s, at(0.3, 0, 0.0), cyl, Transform());  // inside, nearest the side
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.3, 1e-12);
  expectNormal(m, -Vec3::UnitX());
}

TEST(Narrowphase, CapsuleCylinder) {
  const Geometry c = Geometry::capsule(0.1, 0.3), cyl = Geometry::cylinder(0.5, 0.5);
  // Lying on the cap: 2 points.
  Manifold m = run(c, at(0.1, 0, 0.59, rot(kPi / 2, Vec3::UnitY())), cyl, Transform());
  ASSERT_EQ(m.count, 2);
  expectNormal(m, -Vec3::UnitZ(), 1e-9);
  expectAllSep(m, -0.01, 1e-9);
  // Parallel to the side: 2 points.
  m = run(c, at(0.59, 0, 0.1), cyl, Transform());
  ASSERT_EQ(m.count, 2);
  expectNormal(m, -Vec3::UnitX(), 1e-6);
  expectAllSep(m, -0.01, 1e-6);
  // Across the side: 1 point.
  m = run(c, at(0.59, 0, 0.1, rot(kPi / 2, Vec3::UnitX())), cyl, Transform());
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.01, 1e-6);
  EXPECT_EQ(run(c, at(0.7, 0, 0.1), cyl, Transform()).count, 0);
}

TEST(Narrowphase, BoxCylinder) {
  const Geometry box = Geometry::box(Vec3(1, 1, 0.5)), cyl = Geometry::cylinder(0.2, 0.4);
  // Lying on the box: the bottom line, 2 points.
  Manifold m = run(box, Transform(), cyl, at(0.1, 0, 0.69, rot(kPi / 2, Vec3::UnitX())));
  ASSERT_EQ(m.count, 2);
  expectNormal(m, Vec3::UnitZ());
  expectAllSep(m, -0.01, 1e-9);
  const Manifold m2 = run(box, Transform(), cyl, at(0.1001, 0, 0.6899, rot(kPi / 2 + 1e-4, Vec3::UnitX())));
  EXPECT_EQ(ids(m), ids(m2));
  // Standing: 4 rim points.
  m = run(box, Transform(), cyl, at(0.1, 0.2, 0.89));
  ASSERT_EQ(m.count, 4);
  expectNormal(m, Vec3::UnitZ());
  expectAllSep(m, -0.01, 1e-9);
  const Manifold m3 = run(box, Transform(), cyl, at(0.1001, 0.2, 0.8899, rot(1e-4, Vec3::UnitX())));
  EXPECT_EQ(ids(m), ids(m3));
  // Tilted onto the rim: the exact deepest point.
  const double th = 0.5;
  m = run(box, Transform(), cyl, at(0, 0, 0.5 + 0.4 * std::cos(th) + 0.2 * std::sin(th) - 0.01, rot(th, Vec3::UnitX())));
  ASSERT_GE(m.count, 1);
  EXPECT_NEAR(minSep(m), -0.01, 1e-6);
  expectNormal(m, Vec3::UnitZ(), 1e-6);
  // Box on the cylinder's cap: 4 points.
  const Geometry small = Geometry::box(Vec3(0.1, 0.1, 0.1));
  m = run(cyl, Transform(), small, at(0, 0.05, 0.49));
  ASSERT_EQ(m.count, 4);
  expectNormal(m, Vec3::UnitZ());
  expectAllSep(m, -0.01, 1e-9);
  EXPECT_EQ(run(box, Transform(), cyl, at(0, 0, 0.91)).count, 0);
}

TEST(Narrowphase, CylinderCylinder) {
  const Geometry cyl = Geometry::cylinder(0.3, 0.2);
  Manifold m = run(cyl, Transform(), cyl, at(0.1, 0, 0.39));  // stacked
  ASSERT_EQ(m.count, 4);
  expectNormal(m, Vec3::UnitZ());
  expectAllSep(m, -0.01, 1e-9);
  const Quat side = rot(kPi / 2, Vec3::UnitX());
  m = run(cyl, at(0, 0, 0, side), cyl, at(0, 0.05, 0.59, side));  // parallel sides
  ASSERT_EQ(m.count, 2);
  expectNormal(m, Vec3::UnitZ(), 1e-4);  // EPA between curved sides
  expectAllSep(m, -0.01, 1e-6);
  m = run(cyl, at(0, 0, 0, side), cyl, at(0, 0, 0.59, rot(kPi / 2, Vec3::UnitY())));  // crossed
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.01, 1e-6);
  m = run(cyl, at(0, 0, 0, side), cyl, at(0, 0, 0.62, rot(kPi / 2, Vec3::UnitY())), 0.05);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, 0.02, 1e-6);
  EXPECT_EQ(run(cyl, Transform(), cyl, at(0, 0, 0.41)).count, 0);
}
