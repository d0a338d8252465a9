// GJK and EPA on convex cores: EPA depth against the boxes' separating axes, a near-touching
// cylinder that is not an overlap, continuity near contact, the start guess and the far bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "narrowphase_test_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::narrowphase_test;

TEST(Narrowphase, EpaDepthMatchesBoxSeparatingAxes) {
  // For two boxes the penetration depth is the least overlap over the 15 SAT axes; EPA and the
  // SAT pair routine must both find it.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  const Geometry a = Geometry::box(Vec3(0.3, 0.2, 0.25)), b = Geometry::box(Vec3(0.2, 0.35, 0.15));
  int compared = 0;
  for (int k = 0; k < 300; ++k) {
    const Transform xa(Vec3(u(rng), u(rng), u(rng)), randomQuat(rng));
    const Transform xb(Vec3(u(rng), u(rng), u(rng)), randomQuat(rng));
    const Mat3 ra = xa.q.toRotationMatrix(), rb = xb.q.toRotationMatrix();
    std::vector<Vec3> axes;
    for (int i = 0; i < 3; ++i) {
      axes.push_back(ra.col(i));
      axes.push_back(rb.col(i));
      for (int j = 0; j < 3; ++j)
        if (ra.col(i).cross(rb.col(j)).norm() > 1e-6) axes.push_back(ra.col(i).cross(rb.col(j)).normalized());
    }
    double sat = -1e9;
    for (const Vec3& l : axes) {
      const double ea = (ra.transpose() * l).cwiseAbs().dot(a.half_extents);
      const double eb = (rb.transpose() * l).cwiseAbs().dot(b.half_extents);
      sat = std::max(sat, std::abs(l.dot(xb.p - xa.p)) - ea - eb);
    }
    if (sat > 0) continue;
    const np::CoreDistance cd = np::coreDistance({&a, xa}, {&b, xb});
    EXPECT_NEAR(cd.distance, sat, 1e-7);
    const Manifold m = run(a, xa, b, xb, 0.5);
    ASSERT_GT(m.count, 0);
    // A face reference is preferred over an edge axis by up to 1e-3, so the clipped points may
    // be that much deeper than the true depth.
    EXPECT_NEAR(minSep(m), sat, 1.5e-3);
    ++compared;
  }
  EXPECT_GT(compared, 100);
}

TEST(Narrowphase, GjkNearTouchingCylinderIsNotAnOverlap) {
  // Scene c (ragdoll15, yaw 1e-3, step 2129): a thigh cylinder 13.8 mm from its own torso box.
  // GJK crept along the cylinder's rim to round-off, piled up near-duplicate points, and a flat
  // tetrahedron "contained" the origin: EPA then gave -12.8 mm, and the position projection
  // pushed the limbs 6 mm apart (anchor error 1.05 mm). A support plane had already separated
  // the two, so the distance must stay positive.
  const Geometry box = Geometry::box(Vec3(0.11, 0.17, 0.21)), cyl = Geometry::cylinder(0.07, 0.18);
  const Transform xo(Vec3(0.29768857951775174, -1.336673316905763, 0.28458904264277374),
                     Quat(0.32325357376984309, -0.17250480706725255, -0.77208235355712918,
                          0.51926684653403299));
  const Transform xt(Vec3(0.34431019939632762, -0.86871252888910788, 0.1930651429703571),
                     Quat(-0.047934003136043415, 0.29505365313326859, -0.61007736588028427,
                          0.73379239622432746));
  const np::CoreDistance cd = np::coreDistance({&box, xo}, {&cyl, xt});
  EXPECT_NEAR(cd.distance, 0.013805, 2e-6);
  EXPECT_NEAR((cd.pb - cd.pa).norm(), cd.distance, 1e-6);
  const Manifold m = run(box, xo, cyl, xt, 0.02);
  ASSERT_GT(m.count, 0);
  EXPECT_NEAR(minSep(m), 0.013805, 1e-4);
}

TEST(Narrowphase, GjkDistanceIsContinuousNearContact) {
  // Random box / cylinder / thin-plate pairs placed from -1 to 3 cm apart: moving one by
  // 0.17 um changes the core distance by about as much, never by a jump (the flat-tetrahedron
  // case above; the old loop gave 1 jump in these 30 000 and 5 in 300 000).
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  const Geometry shapes[3] = {Geometry::box(Vec3(0.11, 0.17, 0.21)), Geometry::cylinder(0.07, 0.18),
                              Geometry::box(Vec3(0.05, 0.3, 0.02))};
  int jumps = 0;
  for (int it = 0; it < 30000; ++it) {
    const int ia = it % 3, ib = ia == 0 && (it / 3) % 3 == 0 ? 1 : (it / 3) % 3;
    const Transform xa(Vec3::Zero(), Quat(u(rng), u(rng), u(rng), u(rng)).normalized());
    const Quat qb = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
    const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
    const np::ConvexCore ca{&shapes[ia], xa};
    double lo = 0.0, hi = 2.0;  // bisect for 1 cm apart along dir
    for (int k = 0; k < 40; ++k) {
      const double mid = 0.5 * (lo + hi);
      (np::coreDistance(ca, {&shapes[ib], Transform(mid * dir, qb)}).distance > 0.01 ? hi : lo) = mid;
    }
    const Transform xb((hi + 0.02 * u(rng)) * dir, qb);
    const Transform xb2(xb.p + 1e-7 * Vec3(u(rng), u(rng), u(rng)), qb);
    const double d0 = np::coreDistance(ca, {&shapes[ib], xb}).distance;
    const double d1 = np::coreDistance(ca, {&shapes[ib], xb2}).distance;
    if (std::abs(d1 - d0) > 1e-5) {
      ++jumps;
      ADD_FAILURE() << "pair " << ia << "-" << ib << ": " << d0 << " -> " << d1;
    }
  }
  EXPECT_EQ(jumps, 0);
}

TEST(Narrowphase, GjkGuessOnlyChangesWhereItStarts) {
  // World passes last step's normal as GJK's first search direction. Any guess (the answer,
  // its opposite, a random one) must give the same distance and normal as none, to the
  // tolerance (1e-7 m), for box / cylinder / plate pairs from 1 cm overlap to 3 cm apart.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const Geometry shapes[3] = {Geometry::box(Vec3(0.11, 0.17, 0.21)), Geometry::cylinder(0.07, 0.18),
                              Geometry::box(Vec3(0.05, 0.3, 0.02))};
  double worst_d = 0, worst_n = 0;
  for (int it = 0; it < 3000; ++it) {
    const int ia = it % 3, ib = ia == 0 && (it / 3) % 3 == 0 ? 1 : (it / 3) % 3;
    const np::ConvexCore ca{&shapes[ia], Transform(Vec3::Zero(), Quat(u(rng), u(rng), u(rng), u(rng)).normalized())};
    const Quat qb = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
    const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
    double lo = 0.0, hi = 2.0;  // bisect for touching along dir, then move by -1..3 cm
    for (int k = 0; k < 40; ++k) {
      const double mid = 0.5 * (lo + hi);
      (np::coreDistance(ca, {&shapes[ib], Transform(mid * dir, qb)}).distance > 0 ? hi : lo) = mid;
    }
    const np::ConvexCore cb{&shapes[ib], Transform((hi + 0.01 + 0.02 * u(rng)) * dir, qb)};
    const np::CoreDistance ref = np::coreDistance(ca, cb);
    const Vec3 opposite = -ref.normal, random = Vec3(u(rng), u(rng), u(rng));
    for (const Vec3* g : {&ref.normal, &opposite, &random}) {
      const np::CoreDistance cd = np::coreDistance(ca, cb, g);
      worst_d = std::max(worst_d, std::abs(cd.distance - ref.distance));
      if (ref.distance > 1e-3) worst_n = std::max(worst_n, (cd.normal - ref.normal).norm());
    }
  }
  EXPECT_LT(worst_d, 3e-7);
  EXPECT_LT(worst_n, 1e-2);
  std::printf("[ gjk      ] guessed vs unguessed: distance %.1e m, normal %.1e\n", worst_d, worst_n);
}

TEST(Narrowphase, GjkFarStopsOnlyBeyondTheBound) {
  // collideConvex lets GJK stop once it proves the cores farther apart than the speculative
  // band. Where it does not stop early the answer must be the full one, bit for bit (the same
  // iterations); an early stop must return a lower bound beyond `far` and at most the distance.
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  const Geometry shapes[3] = {Geometry::box(Vec3(0.11, 0.17, 0.21)), Geometry::cylinder(0.07, 0.18),
                              Geometry::capsule(0.05, 0.2)};
  int early = 0, same = 0;
  for (int it = 0; it < 3000; ++it) {
    const Quat qa = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
    const Quat qb = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
    const np::ConvexCore ca{&shapes[it % 3], Transform(Vec3::Zero(), qa)};
    const np::ConvexCore cb{&shapes[(it / 3) % 3], Transform(0.7 * Vec3(u(rng), u(rng), u(rng)), qb)};
    const double far = 0.02 + 0.1 * std::abs(u(rng));
    const Vec3 guess = Vec3(u(rng), u(rng), u(rng));
    const np::CoreDistance ref = np::coreDistance(ca, cb, &guess);
    const np::CoreDistance cd = np::coreDistance(ca, cb, &guess, far);
    if (cd.distance == ref.distance && cd.normal == ref.normal) {
      ++same;
    } else {
      ++early;
      EXPECT_GT(cd.distance, far);
      EXPECT_LE(cd.distance, ref.distance + 1e-12);
      EXPECT_NEAR(cd.normal.norm(), 1.0, 1e-12);
    }
    if (ref.distance <= far) {
      EXPECT_EQ(cd.distance, ref.distance) << "it " << it;
    }
  }
  EXPECT_GT(early, 100);  // the test reaches both cases
  EXPECT_GT(same, 100);
  std::printf("[ gjk      ] far bound: %d early stops, %d full answers\n", early, same);
}
