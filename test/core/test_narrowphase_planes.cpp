// Narrowphase against planes: spheres, boxes (flat, edge, corner), capsules, cylinders (both
// cap bottoms kept when lying), hulls, and plane-plane (never a contact).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "narrowphase_test_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::narrowphase_test;

TEST(Narrowphase, PlaneSphere) {
  const Geometry s = Geometry::sphere(0.5);
  Manifold m = run(kGround, Transform(), s, at(1, 2, 0.4));
  ASSERT_EQ(m.count, 1);
  expectNormal(m, Vec3::UnitZ());
  EXPECT_NEAR(m.points[0].separation, -0.1, 1e-12);
  EXPECT_TRUE(m.points[0].point.isApprox(Vec3(1, 2, -0.05)));
  m = run(kGround, Transform(), s, at(0, 0, 0.6), 0.2);  // speculative
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, 0.1, 1e-12);
  EXPECT_EQ(run(kGround, Transform(), s, at(0, 0, 0.6), 0.05).count, 0);
}

TEST(Narrowphase, PlaneOffsetAndPlacedByBody) {
  // Plane z = 1 in a body rotated to face +x: the plane becomes x = 1 (solid below x = 1).
  const Geometry p = Geometry::plane(Vec3::UnitZ(), 1);
  const Transform xp(Vec3::Zero(), Quat::FromTwoVectors(Vec3::UnitZ(), Vec3::UnitX()));
  const Manifold m = run(p, xp, Geometry::sphere(0.25), at(1.2, 0, 0));
  ASSERT_EQ(m.count, 1);
  expectNormal(m, Vec3::UnitX());
  EXPECT_NEAR(m.points[0].separation, -0.05, 1e-12);
}

TEST(Narrowphase, PlaneBoxFlatEdgeCorner) {
  const Geometry box = Geometry::box(Vec3(0.5, 0.5, 0.5));
  Manifold m = run(kGround, Transform(), box, at(0, 0, 0.49));
  ASSERT_EQ(m.count, 4);
  expectAllSep(m, -0.01);
  expectNormal(m, Vec3::UnitZ());
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.points[i].point.z(), -0.005, 1e-12);

  m = run(kGround, Transform(), box, at(0, 0, 0.5 * std::sqrt(2.0) - 0.01, rot(kPi / 4, Vec3::UnitX())));
  ASSERT_EQ(m.count, 2);
  expectAllSep(m, -0.01);

  m = run(kGround, Transform(), box, at(0, 0, 0.5 * std::sqrt(3.0) - 0.01, kCornerDown));
  ASSERT_EQ(m.count, 1);
  expectAllSep(m, -0.01);

  EXPECT_EQ(run(kGround, Transform(), box, at(0, 0, 0.51)).count, 0);
  m = run(kGround, Transform(), box, at(0, 0, 0.502));  // speculative
  ASSERT_EQ(m.count, 4);
  expectAllSep(m, 0.002);
}

TEST(Narrowphase, PlaneBoxIdsStable) {
  const Geometry box = Geometry::box(Vec3(0.3, 0.2, 0.1));
  const Manifold m1 = run(kGround, Transform(), box, at(0, 0, 0.099, rot(0.001, Vec3::UnitY())));
  const Manifold m2 = run(kGround, Transform(), box, at(1e-4, -1e-4, 0.0985, rot(-0.001, Vec3::UnitY())));
  ASSERT_EQ(m1.count, 4);
  EXPECT_EQ(ids(m1), ids(m2));
}

TEST(Narrowphase, PlaneCapsule) {
  const Geometry cap = Geometry::capsule(0.1, 0.5);
  Manifold m = run(kGround, Transform(), cap, at(0, 0, 0.09, rot(kPi / 2, Vec3::UnitY())));
  ASSERT_EQ(m.count, 2);
  expectAllSep(m, -0.01);
  m = run(kGround, Transform(), cap, at(0, 0, 0.59));  // standing
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.01, 1e-12);
}

TEST(Narrowphase, PlaneCylinder) {
  const double r = 0.2, h = 0.4;
  const Geometry cyl = Geometry::cylinder(r, h);
  // Lying on its side: the two ends of the bottom line.
  Manifold m = run(kGround, Transform(), cyl, at(0, 0, r - 0.01, rot(kPi / 2, Vec3::UnitX())));
  ASSERT_EQ(m.count, 2);
  expectAllSep(m, -0.01);
  EXPECT_NEAR(std::abs(m.points[0].point.y() - m.points[1].point.y()), 2 * h, 1e-9);
  // Standing on its cap: 4 rim points.
  m = run(kGround, Transform(), cyl, at(0, 0, h - 0.01));
  ASSERT_EQ(m.count, 4);
  expectAllSep(m, -0.01);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.points[i].point.head<2>().norm(), r, 1e-12);
  // Tilted onto its rim: the exact lowest rim point.
  const double th = 0.6;
  m = run(kGround, Transform(), cyl, at(0, 0, h * std::cos(th) + r * std::sin(th) - 0.01, rot(th, Vec3::UnitX())));
  ASSERT_GE(m.count, 1);
  ASSERT_LE(m.count, 2);
  EXPECT_NEAR(minSep(m), -0.01, 1e-12);
  EXPECT_EQ(run(kGround, Transform(), cyl, at(0, 0, h + 0.01)).count, 0);
}

// A cylinder lying on the ground, rolled 45 deg about its axis so that two rim samples of each
// cap lie within the world's 2 cm speculative distance (6 candidates for 4 slots), and tilted
// 1e-4 rad so that one cap is the deeper: the reduced manifold must keep the bottom of BOTH
// caps. Unweighted reduction kept a rim point 1.2 cm up instead of the shallower cap's bottom;
// that cap sank, became the deeper one, and a resting forearm rocked by 24 um every step.
TEST(Narrowphase, PlaneCylinderLyingKeepsBothCapBottoms) {
  const double r = 0.04, h = 0.11, pen = 0.0005, tilt = 1e-4, spec = 0.02;
  const Geometry cyl = Geometry::cylinder(r, h);
  const Quat q = rot(tilt, Vec3::UnitX()) * rot(kPi / 2, Vec3::UnitX()) * rot(kPi / 4, Vec3::UnitZ());
  const Manifold m = run(kGround, Transform(), cyl, at(0, 0, r - pen, q), spec);
  ASSERT_EQ(m.count, 4);
  for (const double cap : {-1.0, 1.0}) {
    const Vec3 bottom = at(0, 0, r - pen, q).apply(Vec3(0, 0, cap * h)) - r * Vec3::UnitZ();
    double nearest = 1e9;
    for (int i = 0; i < m.count; ++i) nearest = std::min(nearest, (m.points[i].point - bottom).norm());
    EXPECT_LT(nearest, 1e-3) << "cap " << cap << ": its bottom point is missing";
  }
  EXPECT_LT(minSep(m), -pen + 1e-6);
}

TEST(Narrowphase, PlaneHullAndPlanePlane) {
  const Geometry hull = Geometry::convexHull(cubeCorners(Vec3(0.5, 0.5, 0.5)));
  Manifold m = run(kGround, Transform(), hull, at(0, 0, 0.49));
  ASSERT_EQ(m.count, 4);
  expectAllSep(m, -0.01);
  m = run(kGround, Transform(), hull, at(0, 0, 0.5 * std::sqrt(3.0) - 0.01, kCornerDown));
  ASSERT_EQ(m.count, 1);
  EXPECT_EQ(run(kGround, Transform(), kGround, at(0, 0, -1)).count, 0);

  // A hull with far more vertices under the plane than a manifold buffer holds keeps the deepest.
  std::vector<Vec3> ball;
  for (int i = 0; i <= 30; ++i)
    for (int j = 0; j < 60; ++j) {
      const double th = kPi * i / 30, ph = kPi * j / 30;
      ball.push_back(Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), -std::cos(th)));
    }
  const Geometry round = Geometry::convexHull(ball);
  ASSERT_TRUE(round.hull);
  m = run(kGround, Transform(), round, at(0, 0, 0.5), 0.5);
  ASSERT_EQ(m.count, 4);
  EXPECT_NEAR(minSep(m), -0.5, 1e-12);
}
