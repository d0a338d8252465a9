// The joint angle kernel (joint_angles_lanes.hpp): its atan2 and asin against libm's, and its
// widths against one joint at a time.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "joint_angles.hpp"
#include "joint_angles_lanes.hpp"

using namespace ragdoll_sim;

namespace {
// |a - b| in units of the last place of b (1 for a wrong sign or class).
double ulps(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0.0 : 1e300;
  if (a == b) return std::signbit(a) == std::signbit(b) ? 0.0 : 1e300;
  const double ulp = std::nextafter(std::abs(b), std::numeric_limits<double>::infinity()) -
                     std::abs(b);
  return std::abs(a - b) / ulp;
}
uint64_t bits(double x) {
  uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
Quat randomQuat(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Quat(n(rng), n(rng), n(rng), n(rng)).normalized();
}
}  // namespace

// Every quadrant, ratios from 1e-12 to 1e12 around the branch points (|y| = |x|, t = 0.66),
// the axes and the signed zeros: within 2 ulp of the correctly rounded atan2.
TEST(JointAnglesLanes, Atan2IsWithinTwoUlpOfLibm) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(-12.0, 12.0);
  double worst = 0.0;
  const auto check = [&](double y, double x) {
    const double d = ulps(laneAtan2(y, x), std::atan2(y, x));
    worst = std::max(worst, d);
    ASSERT_LE(d, 2.0) << "atan2(" << y << ", " << x << ")";
  };
  for (int i = 0; i < 200000; ++i) check(u(rng), u(rng));
  for (int i = 0; i < 100000; ++i) check(u(rng) * std::pow(10.0, e(rng)), u(rng));
  for (int i = 0; i < 20000; ++i) {
    const double x = u(rng), t = 0.66 * (1.0 + 1e-6 * u(rng));
    check(x * t, x);
    check(x, x * (1.0 + 1e-9 * u(rng)));
  }
  for (const double y : {0.0, -0.0, 1.0, -1.0, 1e-300, -1e-300})
    for (const double x : {0.0, -0.0, 1.0, -1.0, 1e-300, -1e-300}) check(y, x);
  EXPECT_GT(worst, 0.0);  // not libm itself
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(laneAtan2(nan, 1.0)));
  EXPECT_TRUE(std::isnan(laneAtan2(1.0, nan)));
}

TEST(JointAnglesLanes, AsinIsWithinTwoUlpOfLibm) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200000; ++i) {
    const double s = i % 4 ? u(rng) : std::copysign(1.0 - 1e-6 * std::abs(u(rng)), u(rng));
    ASSERT_LE(ulps(laneAsin(s), std::asin(s)), 2.0) << "asin(" << s << ")";
  }
  for (const double s : {0.0, -0.0, 1.0, -1.0, 0.5, -0.5})
    EXPECT_LE(ulps(laneAsin(s), std::asin(s)), 2.0) << "asin(" << s << ")";
}

// Eleven joints at once (groups of four or two and one alone, whatever the CPU) give each
// joint's bits of being computed alone; a ball at gimbal lock reports it and keeps its rows.
TEST(JointAnglesLanes, TheWidthsGiveTheBitsOfOneJoint) {
  std::mt19937_64 rng(9);
  constexpr int kJoints = 11;
  std::vector<Quat> q(6 * kJoints), basis(kJoints);
  for (Quat& x : q) x = randomQuat(rng);
  for (Quat& x : basis) x = randomQuat(rng);
  std::vector<Vec3> axis(kJoints), perp(kJoints);
  std::vector<double> sign(kJoints);
  for (int k = 0; k < kJoints; ++k) {
    axis[k] = randomQuat(rng) * Vec3::UnitX();
    perp[k] = anyPerpendicular(axis[k]);
    sign[k] = k % 3 ? 1.0 : -1.0;
  }
  // joint 4's frames: fb = fa qP Rx(0.3) Ry(pi/2) qP^-1, t1 at the lock
  const Quat lock = Eigen::AngleAxisd(0.3, Vec3::UnitX()) * Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY());
  q[4 * 6 + 0] = q[4 * 6 + 1] = q[4 * 6 + 3] = q[4 * 6 + 4] = Quat::Identity();
  q[4 * 6 + 5] = q[4 * 6 + 2] * basis[4] * lock * basis[4].conjugate();
  const auto inputs = [&](int k) {
    const Quat* f = &q[6 * k];
    return frameInputs(f[0], f[1], f[2], f[3], f[4], f[5]);
  };
  struct Out {
    double row[3], angle, angles[3], rows[9], ok;
  };
  const auto run = [&](std::vector<Out>& out, int first, int count) {
    std::vector<HingeAngleJob> hinges;
    std::vector<EulerAngleJob> balls;
    for (int k = first; k < first + count; ++k) {
      Out& o = out[k];
      std::fill(std::begin(o.rows), std::end(o.rows), 7.0);
      hinges.push_back({inputs(k), axis[k].data(), perp[k].data(), o.row, &o.angle});
      balls.push_back({inputs(k), basis[k].coeffs().data(), &sign[k], o.angles, o.rows, &o.ok});
    }
    hingeAngles(hinges.data(), count);
    eulerAngles(balls.data(), count);
  };
  std::vector<Out> together(kJoints), alone(kJoints);
  run(together, 0, kJoints);
  for (int k = 0; k < kJoints; ++k) run(alone, k, 1);
  for (int k = 0; k < kJoints; ++k) {
    const Out &a = together[k], &b = alone[k];
    for (int j = 0; j < 3; ++j) EXPECT_EQ(bits(a.row[j]), bits(b.row[j])) << k;
    EXPECT_EQ(bits(a.angle), bits(b.angle)) << k;
    for (int j = 0; j < 3; ++j) EXPECT_EQ(bits(a.angles[j]), bits(b.angles[j])) << k;
    for (int j = 0; j < 9; ++j) EXPECT_EQ(bits(a.rows[j]), bits(b.rows[j])) << k;
    EXPECT_EQ(a.ok, b.ok) << k;
    EXPECT_EQ(a.ok, k == 4 ? 0.0 : 1.0) << k;
  }
  EXPECT_EQ(together[4].rows[0], 7.0);  // left as they were
  EXPECT_NEAR(together[4].angles[1], M_PI / 2, 1e-6);
}

// The kernel's angles of known rotations: a hinge turned by theta about its axis, and Euler
// angles composed about the basis' axes.
TEST(JointAnglesLanes, AnglesOfKnownRotations) {
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Quat fa = randomQuat(rng);
    const Vec3 axis = randomQuat(rng) * Vec3::UnitZ();
    const double theta = 3.0 * u(rng);
    const Quat fb = fa * Quat(Eigen::AngleAxisd(theta, axis));
    Vec3 row;
    EXPECT_NEAR(hingeAngle(frameInputs(fa, fb), axis, anyPerpendicular(axis), &row), theta, 1e-12);
    EXPECT_LT((row - fa * axis).norm(), 1e-15);
    const EulerBasis basis;  // x, y, z
    const Vec3 t(3.0 * u(rng), 1.5 * u(rng), 3.0 * u(rng));
    const Quat rel = Eigen::AngleAxisd(t[0], Vec3::UnitX()) * Eigen::AngleAxisd(t[1], Vec3::UnitY()) *
                     Eigen::AngleAxisd(t[2], Vec3::UnitZ());
    EXPECT_LT((basis.angles(fa, fa * rel) - t).norm(), 1e-12) << t.transpose();
  }
}
