// Narrowphase over random poses of every shape pair: swapped arguments flip the normal, all
// results finite and consistent with closed-form signed distances, and separated distances
// match sampled surface distances.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "narrowphase_test_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::narrowphase_test;

namespace {

std::vector<Geometry> allShapes() {
  return {Geometry::sphere(0.3),
          Geometry::capsule(0.2, 0.3),
          Geometry::box(Vec3(0.3, 0.2, 0.25)),
          Geometry::cylinder(0.25, 0.3),
          Geometry::convexHull({Vec3(-0.3, -0.2, -0.2), Vec3(0.3, -0.25, -0.2), Vec3(0, 0.35, -0.2),
                                Vec3(0.05, 0.0, 0.35), Vec3(0.2, 0.2, 0.1), Vec3(-0.2, 0.1, 0.2)}),
          Geometry::plane(Vec3(0.1, 0.2, 1), -0.1)};
}

// Signed distance from x (world) to a placed shape, independent closed forms.
double sdf(const Geometry& g, const Transform& t, const Vec3& x) {
  const Vec3 p = t.applyInverse(x);
  switch (g.type) {
    case ShapeType::Sphere: return p.norm() - g.radius;
    case ShapeType::Capsule: {
      const Vec3 q(0, 0, std::min(g.half_height, std::max(-g.half_height, p.z())));
      return (p - q).norm() - g.radius;
    }
    case ShapeType::Box: {
      const Vec3 q = p.cwiseAbs() - g.half_extents;
      return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
    }
    case ShapeType::Cylinder: {
      const Eigen::Vector2d d(p.head<2>().norm() - g.radius, std::abs(p.z()) - g.half_height);
      return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
    }
    case ShapeType::Plane: return g.normal.dot(p) - g.offset;
    case ShapeType::ConvexHull: break;
  }
  return 0;
}

// Points on the surface of a placed shape (for a brute-force distance bound).
std::vector<Vec3> surfaceSamples(const Geometry& g, const Transform& t) {
  std::vector<Vec3> out;
  const int n = 24;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double th = kPi * i / n, ph = kPi * j / n;
      const Vec3 d(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
      // Project the ray from the origin along d onto the surface by bisection on the sdf.
      double lo = 0, hi = 5;
      for (int k = 0; k < 50; ++k) {
        const double mid = 0.5 * (lo + hi);
        (sdf(g, Transform(), mid * d) < 0 ? lo : hi) = mid;
      }
      out.push_back(t.apply(lo * d));
    }
  return out;
}

}  // namespace

TEST(Narrowphase, SwappedArgumentsFlipNormal) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const auto shapes = allShapes();
  int touching = 0;
  for (size_t i = 0; i < shapes.size(); ++i)
    for (size_t j = 0; j < shapes.size(); ++j) {
      if (shapes[i].type == ShapeType::Plane && shapes[j].type == ShapeType::Plane) continue;
      for (int k = 0; k < 30; ++k) {
        const Transform xa(Vec3(u(rng), u(rng), u(rng)), randomQuat(rng));
        const Transform xb(Vec3(u(rng), u(rng), u(rng)), randomQuat(rng));
        expectSymmetric(shapes[i], xa, shapes[j], xb, 0.02);
        touching += run(shapes[i], xa, shapes[j], xb).count > 0;
      }
    }
  EXPECT_GT(touching, 200);
}

TEST(Narrowphase, FuzzAllPairsFiniteAndConsistent) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  const auto shapes = allShapes();
  for (const Geometry& a : shapes)
    for (const Geometry& b : shapes) {
      if (a.type == ShapeType::Plane && b.type == ShapeType::Plane) continue;
      for (int k = 0; k < 300; ++k) {
        const Transform xa(Vec3(u(rng), u(rng), u(rng)), randomQuat(rng));
        const Transform xb(Vec3(u(rng), u(rng), u(rng)), randomQuat(rng));
        const double spec = 0.05;
        const Manifold m = run(a, xa, b, xb, spec);
        ASSERT_LE(m.count, 4);
        if (m.count == 0) continue;
        ASSERT_TRUE(m.normal.allFinite());
        ASSERT_NEAR(m.normal.norm(), 1.0, 1e-9) << shapeTypeName(a.type) << "-" << shapeTypeName(b.type);
        for (int i = 0; i < m.count; ++i) {
          ASSERT_TRUE(m.points[i].point.allFinite());
          ASSERT_TRUE(std::isfinite(m.points[i].separation));
          ASSERT_LT(m.points[i].separation, spec);
          ASSERT_GT(m.points[i].separation, -2.0);
        }
        // A sphere's separation is its centre's signed distance to the other shape minus r.
        if (a.type == ShapeType::Sphere && b.type != ShapeType::ConvexHull) {
          EXPECT_NEAR(minSep(m), sdf(b, xb, xa.p) - a.radius, 1e-6) << shapeTypeName(b.type);
        }
      }
    }
}

TEST(Narrowphase, FuzzSeparatedDistanceMatchesSampling) {
  // For separated pairs the deepest separation is the true distance: never above the sampled
  // surface distance, and not below it by more than the sampling resolution.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto shapes = allShapes();
  int checked = 0;
  for (size_t i = 1; i < 4; ++i)
    for (size_t j = 1; j < 4; ++j)
      for (int k = 0; k < 8; ++k) {
        const Transform xa(Vec3::Zero(), randomQuat(rng));
        const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
        const Transform xb(0.75 * dir, randomQuat(rng));
        const Manifold m = run(shapes[i], xa, shapes[j], xb, 1.0);
        if (m.count == 0 || minSep(m) <= 0.02) continue;
        const auto pa = surfaceSamples(shapes[i], xa), pb = surfaceSamples(shapes[j], xb);
        double best = 1e9;
        for (const Vec3& p : pa)
          for (const Vec3& q : pb) best = std::min(best, (p - q).norm());
        EXPECT_LE(minSep(m), best + 1e-9) << shapeTypeName(shapes[i].type) << "-" << shapeTypeName(shapes[j].type);
        EXPECT_GE(minSep(m), best - 0.06) << shapeTypeName(shapes[i].type) << "-" << shapeTypeName(shapes[j].type);
        ++checked;
      }
  EXPECT_GT(checked, 20);
}
