// Helpers shared by the narrowphase tests (test_narrowphase_*.cpp): placing shapes, running
// one pair, and checking a manifold's points, normal, ids and argument-order symmetry.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "gjk.hpp"
#include "narrowphase.hpp"

namespace ragdoll_sim {
namespace narrowphase_test {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kSpec = 0.005;

inline Transform at(double x, double y, double z, const Quat& q = Quat::Identity()) {
  return Transform(Vec3(x, y, z), q);
}
inline Quat rot(double angle, const Vec3& axis) {
  return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

inline Manifold run(const Geometry& a, const Transform& xa, const Geometry& b,
                    const Transform& xb, double spec = kSpec) {
  Manifold m;
  collide(a, xa, b, xb, spec, m);
  return m;
}

inline double minSep(const Manifold& m) {
  double s = 1e9;
  for (int i = 0; i < m.count; ++i) s = std::min(s, m.points[i].separation);
  return s;
}

// Every point has the given separation (within tol).
inline void expectAllSep(const Manifold& m, double sep, double tol = 1e-9) {
  for (int i = 0; i < m.count; ++i) EXPECT_NEAR(m.points[i].separation, sep, tol) << "point " << i;
}

inline void expectNormal(const Manifold& m, const Vec3& n, double tol = 1e-9) {
  EXPECT_LT((m.normal - n).norm(), tol) << m.normal.transpose() << " vs " << n.transpose();
}

inline std::vector<uint32_t> ids(const Manifold& m) {
  std::vector<uint32_t> v;
  for (int i = 0; i < m.count; ++i) v.push_back(m.points[i].id);
  std::sort(v.begin(), v.end());
  return v;
}

// Both argument orders: same points and separations, opposite normals.
// Pairs with a cylinder use EPA on curved surfaces, where the depth is stationary in the normal
// direction: the normal is only as accurate as the square root of the depth tolerance.
inline void expectSymmetric(const Geometry& a, const Transform& xa, const Geometry& b,
                            const Transform& xb, double spec = kSpec) {
  const bool curved = a.type == ShapeType::Cylinder || b.type == ShapeType::Cylinder;
  const double tol = curved ? 1e-3 : 1e-6;
  const Manifold m1 = run(a, xa, b, xb, spec), m2 = run(b, xb, a, xa, spec);
  ASSERT_EQ(m1.count, m2.count) << shapeTypeName(a.type) << "-" << shapeTypeName(b.type);
  if (m1.count == 0) return;
  EXPECT_LT((m1.normal + m2.normal).norm(), tol) << shapeTypeName(a.type) << "-" << shapeTypeName(b.type);
  EXPECT_NEAR(minSep(m1), minSep(m2), 1e-6);
  for (int i = 0; i < m1.count; ++i) {
    double best = 1e9;
    for (int j = 0; j < m2.count; ++j) best = std::min(best, (m1.points[i].point - m2.points[j].point).norm());
    EXPECT_LT(best, tol) << shapeTypeName(a.type) << "-" << shapeTypeName(b.type);
  }
}

inline std::vector<Vec3> cubeCorners(const Vec3& h) {
  std::vector<Vec3> p;
  for (int i = 0; i < 8; ++i)
    p.push_back(Vec3(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z()));
  return p;
}

inline const Geometry kGround = Geometry::plane(Vec3::UnitZ(), 0);
inline const Quat kCornerDown = Quat::FromTwoVectors(Vec3(-1, -1, -1).normalized(), -Vec3::UnitZ());

inline Quat randomQuat(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
}

}  // namespace narrowphase_test
}  // namespace ragdoll_sim
