// Contact points (a sphere of radius 0, Drake's convention) against every shape type: one
// contact at the point, its separation the signed distance to the surface (negative inside),
// the normal the surface's, both argument orders alike, nothing beyond the speculative distance.
#include <random>

#include "narrowphase_test_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::narrowphase_test;

namespace {

const Geometry kPoint = Geometry::sphere(0.0);

// Signed distance of a local point to a box of half extents h (negative inside).
double boxDistance(const Vec3& p, const Vec3& h) {
  const Vec3 q = p.cwiseAbs() - h;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

// Signed distance of a local point to a cylinder about z (radius r, half height hh).
double cylinderDistance(const Vec3& p, double r, double hh) {
  const double dr = std::hypot(p.x(), p.y()) - r, dz = std::abs(p.z()) - hh;
  return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0)) + std::min(std::max(dr, dz), 0.0);
}

// The point at `p` (world) against `shape` at `xs`: one contact with separation `sep`, at the
// point, with the normal (point -> shape) `n`, and the same seen from the shape.
void expectPointContact(const Geometry& shape, const Transform& xs, const Vec3& p, double sep,
                        const Vec3& n, double tol = 1e-6) {
  SCOPED_TRACE(shapeTypeName(shape.type));
  const Manifold m = run(kPoint, at(p.x(), p.y(), p.z()), shape, xs);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, sep, tol);
  expectNormal(m, n, 1e-3);
  // The contact point is midway between the point and the shape's surface.
  EXPECT_LT((m.points[0].point - (p + 0.5 * sep * n)).norm(), 1e-4);
  expectSymmetric(kPoint, at(p.x(), p.y(), p.z()), shape, xs);
}

}  // namespace

TEST(NarrowphasePoints, PlaneSpeculativeTouchingAndBelow) {
  // Plane first: the normal points from the plane to the point.
  for (const double z : {0.004, 0.0, -0.003, -0.2}) {
    const Manifold m = run(kGround, Transform(), kPoint, at(0.3, -0.2, z));
    ASSERT_EQ(m.count, 1) << z;
    EXPECT_NEAR(m.points[0].separation, z, 1e-12);
    expectNormal(m, Vec3::UnitZ());
    EXPECT_NEAR(m.points[0].point.z(), 0.5 * z, 1e-12);  // midway to the plane
  }
  EXPECT_EQ(run(kGround, Transform(), kPoint, at(0, 0, 2 * kSpec)).count, 0);
  expectSymmetric(kGround, Transform(), kPoint, at(0.1, 0.2, -0.001));
}

TEST(NarrowphasePoints, Sphere) {
  const Geometry s = Geometry::sphere(0.1);
  expectPointContact(s, Transform(), Vec3(0, 0, 0.103), 0.003, -Vec3::UnitZ());
  expectPointContact(s, Transform(), Vec3(0.097, 0, 0), -0.003, -Vec3::UnitX());
  expectPointContact(s, at(1, 2, 3), Vec3(1, 2, 3) + 0.05 * Vec3(1, 1, 1).normalized(), -0.05,
                     -Vec3(1, 1, 1).normalized());
  EXPECT_EQ(run(kPoint, at(0, 0, 0.1 + 2 * kSpec), s, Transform()).count, 0);
  // Two points: a pair that only meets where they coincide, and never as a NaN.
  const Manifold pp = run(kPoint, at(0, 0, 0), kPoint, at(0, 0, 0));
  for (int i = 0; i < pp.count; ++i) EXPECT_TRUE(pp.points[i].point.allFinite());
  EXPECT_TRUE(pp.normal.allFinite());
}

TEST(NarrowphasePoints, Capsule) {
  const Geometry c = Geometry::capsule(0.05, 0.1);
  expectPointContact(c, Transform(), Vec3(0.047, 0, 0.05), -0.003, -Vec3::UnitX());
  expectPointContact(c, Transform(), Vec3(0, 0.052, -0.02), 0.002, -Vec3::UnitY());
  expectPointContact(c, Transform(), Vec3(0, 0, 0.148), -0.002, -Vec3::UnitZ());  // the cap
  EXPECT_EQ(run(kPoint, at(0.05 + 2 * kSpec, 0, 0), c, Transform()).count, 0);
}

TEST(NarrowphasePoints, Box) {
  const Geometry b = Geometry::box(Vec3(0.1, 0.2, 0.3));
  expectPointContact(b, Transform(), Vec3(0.097, 0.05, 0.1), -0.003, -Vec3::UnitX());
  expectPointContact(b, Transform(), Vec3(0.02, -0.05, 0.304), 0.004, -Vec3::UnitZ());
  EXPECT_EQ(run(kPoint, at(0.1 + 2 * kSpec, 0, 0), b, Transform()).count, 0);
}

TEST(NarrowphasePoints, Cylinder) {
  const Geometry c = Geometry::cylinder(0.1, 0.2);
  expectPointContact(c, Transform(), Vec3(0.02, 0.01, 0.198), -0.002, -Vec3::UnitZ());  // cap
  expectPointContact(c, Transform(), Vec3(0, -0.097, 0.05), -0.003, Vec3::UnitY());    // side
  expectPointContact(c, Transform(), Vec3(0.103, 0, -0.1), 0.003, -Vec3::UnitX());
  EXPECT_EQ(run(kPoint, at(0, 0, 0.2 + 2 * kSpec), c, Transform()).count, 0);
}

TEST(NarrowphasePoints, Hull) {
  const Geometry h = Geometry::convexHull(cubeCorners(Vec3(0.1, 0.1, 0.1)));
  ASSERT_TRUE(h.hull);
  expectPointContact(h, Transform(), Vec3(0.02, 0.01, 0.097), -0.003, -Vec3::UnitZ());
  expectPointContact(h, Transform(), Vec3(0.02, 0.103, 0.01), 0.003, -Vec3::UnitY());
  EXPECT_EQ(run(kPoint, at(0, 0, 0.1 + 2 * kSpec), h, Transform()).count, 0);
}

// Random poses near the surface of a box, a box-shaped hull and a cylinder: the separation is
// the signed distance, inside and out.
TEST(NarrowphasePoints, SeparationIsTheSignedDistanceAtRandomPoses) {
  std::mt19937 rng(58);
  std::uniform_real_distribution<double> u(-0.13, 0.13);
  const Vec3 half(0.1, 0.07, 0.05);
  const Geometry box = Geometry::box(half);
  const Geometry hull = Geometry::convexHull(cubeCorners(half));
  const Geometry cyl = Geometry::cylinder(0.08, 0.06);
  int checked = 0;
  for (int k = 0; k < 3000; ++k) {
    const Transform xs(Vec3(u(rng), u(rng), u(rng)), randomQuat(rng));
    const Vec3 p = xs.apply(Vec3(u(rng), u(rng), u(rng)));
    const Vec3 local = xs.applyInverse(p);
    for (const Geometry* g : {&box, &hull, &cyl}) {
      const double d = g == &cyl ? cylinderDistance(local, cyl.radius, cyl.half_height)
                                 : boxDistance(local, half);
      // Deep inside, the nearest face is ambiguous; within 3 cm of the surface it is not.
      if (d >= kSpec || d < -0.03) continue;
      const Manifold m = run(kPoint, Transform(p, Quat::Identity()), *g, xs);
      ASSERT_EQ(m.count, 1) << shapeTypeName(g->type) << " at " << local.transpose();
      EXPECT_NEAR(m.points[0].separation, d, g == &cyl ? 1e-4 : 1e-6)
          << shapeTypeName(g->type) << " at " << local.transpose();
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
}
