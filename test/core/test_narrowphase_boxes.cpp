// Narrowphase of boxes: sphere and capsule against a box, box-box face, edge and corner
// contacts (separating axes and clipping), stable point ids, a deep rotated base.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "narrowphase_test_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::narrowphase_test;

TEST(Narrowphase, SphereBox) {
  const Geometry s = Geometry::sphere(0.1), box = Geometry::box(Vec3(1, 1, 1));
  Manifold m = run(s, at(0, 0, 1.09), box, Transform());  // on the face
  ASSERT_EQ(m.count, 1);
  expectNormal(m, -Vec3::UnitZ());
  EXPECT_NEAR(m.points[0].separation, -0.01, 1e-12);
  m = run(s, at(1.05, 1.05, 0), box, Transform(), 0.1);  // near an edge
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, 0.05 * std::sqrt(2.0) - 0.1, 1e-12);
  expectNormal(m, -Vec3(1, 1, 0).normalized());
  m = run(s, at(0.7, 0, 0.1), box, Transform());  // centre inside
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.4, 1e-12);
  expectNormal(m, -Vec3::UnitX());
  EXPECT_EQ(run(s, at(0, 0, 1.2), box, Transform()).count, 0);
}

TEST(Narrowphase, CapsuleBox) {
  const Geometry c = Geometry::capsule(0.1, 0.4), box = Geometry::box(Vec3(1, 1, 0.5));
  Manifold m = run(c, at(0.2, 0, 0.59, rot(kPi / 2, Vec3::UnitY())), box, Transform());
  ASSERT_EQ(m.count, 2);
  expectNormal(m, -Vec3::UnitZ());
  expectAllSep(m, -0.01);
  const Manifold m2 = run(c, at(0.2001, 0, 0.5899, rot(kPi / 2 + 1e-4, Vec3::UnitY())), box, Transform());
  EXPECT_EQ(ids(m), ids(m2));
  m = run(c, at(0, 0, 0.99), box, Transform());  // standing
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.01, 1e-9);
  m = run(c, at(0, 0, 0.3, rot(kPi / 2, Vec3::UnitY())), box, Transform());  // core deep inside
  ASSERT_GE(m.count, 1);
  expectNormal(m, -Vec3::UnitZ(), 1e-6);
  EXPECT_NEAR(minSep(m), -0.3, 1e-6);
  EXPECT_EQ(run(c, at(0, 0, 0.62, rot(kPi / 2, Vec3::UnitY())), box, Transform()).count, 0);
}

TEST(Narrowphase, BoxBoxFaceEdgeCorner) {
  const Geometry base = Geometry::box(Vec3(1, 1, 0.5)), cube = Geometry::box(Vec3(0.5, 0.5, 0.5));
  Manifold m = run(base, Transform(), cube, at(0.1, 0.2, 0.98));
  ASSERT_EQ(m.count, 4);
  expectNormal(m, Vec3::UnitZ());
  expectAllSep(m, -0.02);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.points[i].point.z(), 0.49, 1e-12);

  m = run(base, Transform(), cube, at(0, 0, 0.98, rot(kPi / 4, Vec3::UnitZ())));
  ASSERT_EQ(m.count, 4);
  expectAllSep(m, -0.02);

  m = run(base, Transform(), cube, at(0, 0, 0.5 + 0.5 * std::sqrt(2.0) - 0.02, rot(kPi / 4, Vec3::UnitX())));
  ASSERT_EQ(m.count, 2);
  expectNormal(m, Vec3::UnitZ());
  expectAllSep(m, -0.02);

  m = run(base, Transform(), cube, at(0, 0, 0.5 + 0.5 * std::sqrt(3.0) - 0.02, kCornerDown));
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.02, 1e-9);

  // Overhanging: the clipped face keeps the part over the base.
  m = run(base, Transform(), cube, at(1.2, 0, 0.99));
  ASSERT_EQ(m.count, 4);
  for (int i = 0; i < 4; ++i) EXPECT_LE(m.points[i].point.x(), 1 + 1e-12);

  EXPECT_EQ(run(base, Transform(), cube, at(0, 0, 1.02)).count, 0);
  m = run(base, Transform(), cube, at(0, 0, 1.003));
  ASSERT_EQ(m.count, 4);
  expectAllSep(m, 0.003);
}

TEST(Narrowphase, BoxBoxEdgeEdge) {
  const Geometry cube = Geometry::box(Vec3(0.5, 0.5, 0.5));
  const double e = 0.5 * std::sqrt(2.0);
  const Manifold m = run(cube, at(0, 0, 0, rot(kPi / 4, Vec3::UnitX())), cube,
                         at(0.1, -0.1, 2 * e - 0.02, rot(kPi / 4, Vec3::UnitY())));
  ASSERT_EQ(m.count, 1);
  expectNormal(m, Vec3::UnitZ(), 1e-9);
  EXPECT_NEAR(m.points[0].separation, -0.02, 1e-9);
  EXPECT_TRUE(m.points[0].point.isApprox(Vec3(0.1, 0, e - 0.01), 1e-9));
}

TEST(Narrowphase, BoxBoxIdsStable) {
  const Geometry base = Geometry::box(Vec3(1, 1, 0.5)), cube = Geometry::box(Vec3(0.3, 0.3, 0.3));
  const Manifold m1 = run(base, Transform(), cube, at(0.9, 0, 0.79, rot(0.3, Vec3::UnitZ())));
  const Manifold m2 = run(base, Transform(), cube, at(0.9001, -0.0001, 0.7899, rot(0.3001, Vec3::UnitZ())));
  ASSERT_EQ(m1.count, 4);
  EXPECT_EQ(ids(m1), ids(m2));
}

TEST(Narrowphase, BoxBoxRotatedBaseDeep) {
  // A tilted stack: contact normal follows the base's face.
  const Quat q = rot(0.4, Vec3(1, 2, 3));
  const Geometry base = Geometry::box(Vec3(1, 1, 0.5)), cube = Geometry::box(Vec3(0.5, 0.5, 0.5));
  const Transform xa(Vec3(1, 2, 3), q);
  const Transform xb = xa * at(0.1, 0, 0.9);
  const Manifold m = run(base, xa, cube, xb);
  ASSERT_EQ(m.count, 4);
  expectNormal(m, q * Vec3::UnitZ());
  expectAllSep(m, -0.1);
}
