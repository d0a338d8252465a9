// Shapes: volumes and inertias against closed forms, hull construction, bounding boxes.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "narrowphase.hpp"
#include "ragdoll_sim/shape.hpp"

using namespace ragdoll_sim;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<Vec3> cubeCorners(const Vec3& h, const Vec3& shift = Vec3::Zero()) {
  std::vector<Vec3> p;
  for (int i = 0; i < 8; ++i)
    p.push_back(shift + Vec3(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z()));
  return p;
}

// Inertia of a solid of revolution about z with radius profile rho(z) on [z0, z1] (midpoint rule).
Mat3 revolutionInertia(double z0, double z1, const std::function<double(double)>& rho) {
  const int steps = 200000;
  const double dz = (z1 - z0) / steps;
  double ixx = 0, izz = 0;
  for (int i = 0; i < steps; ++i) {
    const double z = z0 + (i + 0.5) * dz, r = rho(z), area = kPi * r * r;
    izz += 0.5 * area * r * r * dz;
    ixx += (0.25 * area * r * r + area * z * z) * dz;
  }
  return Vec3(ixx, ixx, izz).asDiagonal();
}

void expectMatNear(const Mat3& a, const Mat3& b, double tol) {
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), tol) << "\n" << a << "\nvs\n" << b;
}

void expectValidHull(const HullData& h) {
  // Euler characteristic, planarity, outward counter-clockwise faces, convexity.
  EXPECT_EQ(int(h.vertices.size()) - int(h.edges.size()) + int(h.faces.size()), 2);
  ASSERT_EQ(h.edges.size(), h.edge_faces.size());
  for (const auto& ef : h.edge_faces) EXPECT_NE(ef.first, ef.second);
  for (const auto& f : h.faces) {
    ASSERT_GE(f.verts.size(), 3u);
    EXPECT_NEAR(f.normal.norm(), 1.0, 1e-12);
    for (size_t k = 0; k < f.verts.size(); ++k) {
      const Vec3& a = h.vertices[f.verts[k]];
      const Vec3& b = h.vertices[f.verts[(k + 1) % f.verts.size()]];
      const Vec3& c = h.vertices[f.verts[(k + 2) % f.verts.size()]];
      EXPECT_NEAR(f.normal.dot(a), f.offset, 1e-9);
      EXPECT_GT((b - a).cross(c - b).dot(f.normal), 0);
    }
    for (const Vec3& v : h.vertices) EXPECT_LE(f.normal.dot(v), f.offset + 1e-9);
    EXPECT_LT(f.normal.dot(h.centroid), f.offset);
  }
}

}  // namespace

TEST(Shape, TypeNames) {
  EXPECT_STREQ(shapeTypeName(ShapeType::Box), "box");
  EXPECT_STREQ(shapeTypeName(ShapeType::ConvexHull), "convex_hull");
  EXPECT_STREQ(shapeTypeName(ShapeType::Plane), "plane");
}

TEST(Shape, Factories) {
  const Geometry c = Geometry::capsule(0.1, 0.3);
  EXPECT_EQ(c.type, ShapeType::Capsule);
  EXPECT_DOUBLE_EQ(c.radius, 0.1);
  EXPECT_DOUBLE_EQ(c.half_height, 0.3);
  const Geometry p = Geometry::plane(Vec3(0, 0, 2), 4);
  EXPECT_TRUE(p.normal.isApprox(Vec3::UnitZ()));
  EXPECT_DOUBLE_EQ(p.offset, 2);
  EXPECT_EQ(p.volume(), 0);
  EXPECT_TRUE(isUnbounded(p));
}

TEST(Shape, VolumesClosedForm) {
  EXPECT_NEAR(Geometry::sphere(0.5).volume(), 4.0 / 3.0 * kPi * 0.125, 1e-12);
  EXPECT_NEAR(Geometry::box(Vec3(0.1, 0.2, 0.3)).volume(), 0.048, 1e-12);
  EXPECT_NEAR(Geometry::cylinder(0.2, 0.5).volume(), kPi * 0.04 * 1.0, 1e-12);
  EXPECT_NEAR(Geometry::capsule(0.2, 0.5).volume(), kPi * 0.04 * 1.0 + 4.0 / 3.0 * kPi * 0.008,
              1e-12);
}

TEST(Shape, InertiaBoxSphereCylinder) {
  const Geometry box = Geometry::box(Vec3(0.1, 0.2, 0.3));
  const double m = box.volume();
  expectMatNear(box.unitInertia(),
                Vec3(m / 12 * (0.16 + 0.36), m / 12 * (0.04 + 0.36), m / 12 * (0.04 + 0.16)).asDiagonal(),
                1e-14);
  const Geometry s = Geometry::sphere(0.3);
  expectMatNear(s.unitInertia(), Mat3::Identity() * 0.4 * s.volume() * 0.09, 1e-14);
  const Geometry c = Geometry::cylinder(0.2, 0.5);
  expectMatNear(c.unitInertia(), revolutionInertia(-0.5, 0.5, [](double) { return 0.2; }), 1e-8);
  const double mc = c.volume();
  EXPECT_NEAR(c.unitInertia()(2, 2), 0.5 * mc * 0.04, 1e-14);
  EXPECT_NEAR(c.unitInertia()(0, 0), mc * (3 * 0.04 + 1.0) / 12, 1e-14);
}

TEST(Shape, InertiaCapsuleByIntegration) {
  for (double h : {0.0, 0.2, 1.0}) {
    const double r = 0.3;
    const Geometry c = Geometry::capsule(r, h);
    const Mat3 ref = revolutionInertia(-h - r, h + r, [&](double z) {
      const double dz = std::max(0.0, std::abs(z) - h);
      return std::sqrt(std::max(0.0, r * r - dz * dz));
    });
    expectMatNear(c.unitInertia(), ref, 1e-7);
  }
  // Zero length capsule is a sphere.
  expectMatNear(Geometry::capsule(0.3, 0).unitInertia(), Geometry::sphere(0.3).unitInertia(), 1e-14);
}

TEST(Shape, HullOfCubeMatchesBox) {
  const Vec3 h(0.1, 0.2, 0.3);
  const Geometry g = Geometry::convexHull(cubeCorners(h));
  ASSERT_TRUE(g.hull);
  EXPECT_EQ(g.hull->vertices.size(), 8u);
  EXPECT_EQ(g.hull->faces.size(), 6u);
  EXPECT_EQ(g.hull->edges.size(), 12u);
  for (const auto& f : g.hull->faces) EXPECT_EQ(f.verts.size(), 4u);
  expectValidHull(*g.hull);
  const Geometry box = Geometry::box(h);
  EXPECT_NEAR(g.volume(), box.volume(), 1e-14);
  expectMatNear(g.unitInertia(), box.unitInertia(), 1e-14);
}

TEST(Shape, HullIgnoresInteriorFaceAndEdgePoints) {
  std::vector<Vec3> p = cubeCorners(Vec3(1, 1, 1));
  p.push_back(Vec3(0, 0, 0));
  p.push_back(Vec3(1, 0, 0));    // face centre
  p.push_back(Vec3(1, 1, 0));    // edge midpoint
  p.push_back(Vec3(0.3, -1, 0.2));
  p.push_back(Vec3(1, 1, 1));    // duplicate
  const auto h = HullData::build(p);
  ASSERT_TRUE(h);
  EXPECT_EQ(h->vertices.size(), 8u);
  EXPECT_EQ(h->faces.size(), 6u);
  expectValidHull(*h);
}

TEST(Shape, HullOffsetCubeParallelAxis) {
  const Vec3 h(0.5, 0.5, 0.5), shift(1, 2, 3);
  const Geometry g = Geometry::convexHull(cubeCorners(h, shift));
  ASSERT_TRUE(g.hull);
  const double m = g.volume();
  const Mat3 expected = Geometry::box(h).unitInertia() +
                        m * (shift.squaredNorm() * Mat3::Identity() - shift * shift.transpose());
  expectMatNear(g.unitInertia(), expected, 1e-12);
  EXPECT_TRUE(g.hull->centroid.isApprox(shift));
}

TEST(Shape, HullRandomPointsContainsAll) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec3> p;
    for (int i = 0; i < 200; ++i) p.push_back(Vec3(u(rng), u(rng), 0.5 * u(rng)));
    const auto h = HullData::build(p);
    ASSERT_TRUE(h);
    expectValidHull(*h);
    for (const Vec3& x : p)
      for (const auto& f : h->faces) EXPECT_LE(f.normal.dot(x), f.offset + 1e-9);
    // Volume of a hull lies inside the bounding box volume and matches the Euler-consistent
    // tetrahedral sum from another origin (translation invariance).
    Geometry g;
    g.type = ShapeType::ConvexHull;
    g.hull = h;
    std::vector<Vec3> shifted = p;
    for (Vec3& x : shifted) x += Vec3(3, -2, 1);
    EXPECT_NEAR(g.volume(), Geometry::convexHull(shifted).volume(), 1e-12);
    EXPECT_LT(g.volume(), 4.0);
  }
}

TEST(Shape, HullOfSphereSamplesApproachesSphere) {
  std::vector<Vec3> p;
  const int n = 40;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double th = kPi * i / n, ph = kPi * j / n;
      p.push_back(Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
    }
  const Geometry g = Geometry::convexHull(p);
  ASSERT_TRUE(g.hull);
  expectValidHull(*g.hull);
  EXPECT_NEAR(g.volume(), 4.0 / 3.0 * kPi, 0.02 * 4.0);
}

TEST(Shape, HullDegenerateInputs) {
  EXPECT_FALSE(HullData::build({}));
  EXPECT_FALSE(HullData::build({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}));
  EXPECT_FALSE(HullData::build({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0),
                                Vec3(0.5, 0.2, 0)}));  // coplanar
  EXPECT_FALSE(HullData::build({Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2), Vec3(3, 3, 3)}));
  EXPECT_FALSE(Geometry::convexHull({Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 0)}).hull);
}

TEST(Shape, AabbPerType) {
  const Transform rotz(Vec3(1, 2, 3), Quat(Eigen::AngleAxisd(kPi / 4, Vec3::UnitZ())));
  Aabb b = computeAabb(Geometry::box(Vec3(1, 1, 0.5)), rotz);
  EXPECT_TRUE(b.lo.isApprox(Vec3(1 - std::sqrt(2.0), 2 - std::sqrt(2.0), 2.5)));
  EXPECT_TRUE(b.hi.isApprox(Vec3(1 + std::sqrt(2.0), 2 + std::sqrt(2.0), 3.5)));

  const Transform rotx(Vec3::Zero(), Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitX())));
  b = computeAabb(Geometry::cylinder(0.2, 1.0), rotx);  // axis along -y
  EXPECT_TRUE(b.hi.isApprox(Vec3(0.2, 1.0, 0.2)));
  b = computeAabb(Geometry::capsule(0.2, 1.0), rotx);
  EXPECT_TRUE(b.hi.isApprox(Vec3(0.2, 1.2, 0.2)));
  b = computeAabb(Geometry::sphere(0.5), Transform(Vec3(1, 1, 1), Quat::Identity()));
  EXPECT_TRUE(b.lo.isApprox(Vec3(0.5, 0.5, 0.5)));

  const Geometry hull = Geometry::convexHull(cubeCorners(Vec3(1, 1, 0.5)));
  const Aabb bh = computeAabb(hull, rotz);
  const Aabb bb = computeAabb(Geometry::box(Vec3(1, 1, 0.5)), rotz);
  EXPECT_TRUE(bh.lo.isApprox(bb.lo) && bh.hi.isApprox(bb.hi));

  // Cylinder tilted: bound is tight against sampled rim points.
  const Transform tilt(Vec3::Zero(), quatFromRpy(0.3, 0.7, 0.1));
  const Geometry cyl = Geometry::cylinder(0.3, 0.8);
  const Aabb bc = computeAabb(cyl, tilt);
  Vec3 hi = Vec3::Constant(-1e9);
  for (int k = 0; k < 3600; ++k)
    for (double z : {-0.8, 0.8}) {
      const double a = 2 * kPi * k / 3600;
      hi = hi.cwiseMax(tilt.apply(Vec3(0.3 * std::cos(a), 0.3 * std::sin(a), z)));
    }
  EXPECT_TRUE((bc.hi - hi).cwiseAbs().maxCoeff() < 1e-5);

  const Aabb bp = computeAabb(Geometry::plane(Vec3::UnitZ(), 0), Transform());
  EXPECT_TRUE(bp.overlaps(b));
}
