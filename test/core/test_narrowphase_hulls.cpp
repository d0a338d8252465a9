// Narrowphase of convex hulls: a hull box matches the box, hull stacks keep their ids, hulls
// against round shapes and cylinders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "narrowphase_test_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::narrowphase_test;

TEST(Narrowphase, HullMatchesBox) {
  const Vec3 h(0.5, 0.4, 0.3);
  const Geometry box = Geometry::box(h), hull = Geometry::convexHull(cubeCorners(h));
  const Geometry base = Geometry::box(Vec3(1, 1, 0.5));
  const Geometry base_hull = Geometry::convexHull(cubeCorners(Vec3(1, 1, 0.5)));
  const Transform poses[] = {at(0.1, 0.2, 0.78), at(0, 0, 0.5 + 0.5 * std::sqrt(2.0) * 0.9, rot(kPi / 4, Vec3::UnitX())),
                             at(0.3, 0, 0.9, kCornerDown), at(0.2, 0.1, 0.7, rot(0.3, Vec3(1, 1, 0)))};
  for (const Transform& x : poses) {
    const Manifold mb = run(base, Transform(), box, x, 0.1);
    for (const auto& pair : {std::make_pair(&base_hull, &hull), std::make_pair(&base, &hull),
                             std::make_pair(&base_hull, &box)}) {
      const Manifold mh = run(*pair.first, Transform(), *pair.second, x, 0.1);
      ASSERT_EQ(mb.count, mh.count);
      if (mb.count == 0) continue;
      EXPECT_NEAR(minSep(mb), minSep(mh), 1e-9);
      EXPECT_LT((mb.normal - mh.normal).norm(), 1e-9);
    }
  }
}

TEST(Narrowphase, HullStackAndIds) {
  const Geometry hull = Geometry::convexHull(cubeCorners(Vec3(0.5, 0.5, 0.5)));
  const Manifold m = run(hull, Transform(), hull, at(0.2, 0.1, 0.99, rot(0.2, Vec3::UnitZ())));
  ASSERT_EQ(m.count, 4);
  expectNormal(m, Vec3::UnitZ());
  expectAllSep(m, -0.01, 1e-9);
  EXPECT_EQ(ids(m), ids(run(hull, Transform(), hull, at(0.2001, 0.1, 0.9899, rot(0.2001, Vec3::UnitZ())))));
}

TEST(Narrowphase, HullWithRoundShapesAndCylinder) {
  // Square pyramid: base 1x1 at z = 0, apex at z = 1.
  const Geometry pyr = Geometry::convexHull({Vec3(-0.5, -0.5, 0), Vec3(0.5, -0.5, 0), Vec3(0.5, 0.5, 0),
                                             Vec3(-0.5, 0.5, 0), Vec3(0, 0, 1)});
  ASSERT_TRUE(pyr.hull);
  Manifold m = run(Geometry::sphere(0.2), at(0, 0, 1.15), pyr, Transform());  // on the apex
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.05, 1e-9);
  expectNormal(m, -Vec3::UnitZ(), 1e-9);
  m = run(Geometry::sphere(0.2), at(0, 0, -0.19), pyr, Transform());  // under the base
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.01, 1e-9);
  m = run(Geometry::sphere(0.1), at(0, 0, 0.3), pyr, Transform());  // centre inside
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.4, 1e-9);
  // Capsule under the base: 2 points.
  m = run(pyr, Transform(), Geometry::capsule(0.05, 0.2), at(0, 0, -0.04, rot(kPi / 2, Vec3::UnitY())));
  ASSERT_EQ(m.count, 2);
  expectNormal(m, -Vec3::UnitZ(), 1e-9);
  expectAllSep(m, -0.01, 1e-9);
  // Pyramid standing on a cylinder's cap: 4 points.
  m = run(Geometry::cylinder(1, 0.2), Transform(), pyr, at(0, 0, 0.19));
  ASSERT_EQ(m.count, 4);
  expectNormal(m, Vec3::UnitZ(), 1e-9);
  expectAllSep(m, -0.01, 1e-9);
}
