// Ball joint with swing-twist limits: the decomposition and its rates, cone and twist limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "joint_angles.hpp"
#include "joint_test_util.hpp"
#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

// The decomposition recovers known swing / twist angles, and its rows match finite differences.
TEST(SwingTwist, DecompositionAndRates) {
  const Vec3 t = Vec3(1, 2, -0.5).normalized();
  const Vec3 u = anyPerpendicular(t);
  const Quat fa = quatFromRpy(0.4, 0.2, -0.9);
  const double swing = 1.1, twist = -0.6;
  const Quat fb = fa * Quat(Eigen::AngleAxisd(swing, u)) * Quat(Eigen::AngleAxisd(twist, t));
  const SwingTwist st = swingTwist(fa, fb, t);
  EXPECT_NEAR(st.swing, swing, 1e-12);
  EXPECT_NEAR(st.twist, twist, 1e-12);
  ASSERT_TRUE(st.swing_valid && st.twist_valid);
  const Vec3 wrel(0.3, -0.2, 0.5);
  const double eps = 1e-7;
  const Quat fb2 =
      (Quat(Eigen::AngleAxisd(eps * wrel.norm(), wrel.normalized())) * fb).normalized();
  const SwingTwist st2 = swingTwist(fa, fb2, t);
  const double swing_rate = (st2.swing - st.swing) / eps, twist_rate = (st2.twist - st.twist) / eps;
  EXPECT_NEAR(st.swing_row.dot(wrel), swing_rate, 1e-5);
  EXPECT_NEAR(st.twist_row.dot(wrel), twist_rate, 1e-5);
  std::printf("[ swingtw  ] rates: swing %.7f vs fd %.7f, twist %.7f vs fd %.7f\n",
              st.swing_row.dot(wrel), swing_rate, st.twist_row.dot(wrel), twist_rate);
}

namespace {
struct Pendulum {
  World w;
  BodyId bob;
  JointId joint;
  Pendulum(const BallJointDef& extra, const WorldDef& def, const Vec3& omega = Vec3::Zero())
      : w(def) {
    const BodyId base = addStatic(w);
    bob = addDynamic(w, 1.0, diag(0.002, 0.02, 0.02), Transform(), Vec3(0.5, 0, 0), Vec3::Zero(),
                     omega);
    BallJointDef b = extra;
    b.body_a = base;
    b.body_b = bob;
    b.enable_limits = true;
    b.limit_mode = BallLimitMode::SwingTwist;  // twist axis axes[0] = x, along the bob
    joint = w.createBallJoint(b);
  }
};
}  // namespace

// Released from horizontal along the twist axis, the pendulum falls into the 0.5 rad cone and
// rests on its lowest line.
TEST(SwingTwist, ConeStopsPendulumReleasedFromHorizontal) {
  BallJointDef b;
  b.swing_cone_angle = 0.5;
  b.twist_lower = -0.3;
  b.twist_upper = 0.3;
  Pendulum p(b, noSleep());
  double max_swing = 0.0, lo = 1e9, hi = -1e9, anchor = 0.0, t_hit = -1.0;
  for (int i = 0; i < 3000; ++i) {
    p.w.step(kDt);
    const double swing = p.w.ballSwingTwist(p.joint)[0];
    max_swing = std::max(max_swing, swing);
    if (t_hit < 0 && swing > 0.5 - 1e-3) t_hit = p.w.time();
    anchor = std::max(anchor, p.w.jointAnchorError(p.joint).norm());
    if (p.w.time() > 2.0) {
      lo = std::min(lo, swing);
      hi = std::max(hi, swing);
    }
  }
  const auto st = p.w.ballSwingTwist(p.joint);
  EXPECT_LT(max_swing - 0.5, 0.02);
  EXPECT_NEAR(st[0], 0.5, 0.01);
  EXPECT_LT(hi - lo, 0.01);
  EXPECT_LT(std::abs(st[1]), 1e-3);  // no twist load
  EXPECT_LT(anchor, 1e-3);
  // the bob rests at the cone's lowest line: COM at 0.5 (cos 0.5, 0, -sin 0.5)
  EXPECT_LT((p.w.comPosition(p.bob) - 0.5 * Vec3(std::cos(0.5), 0, -std::sin(0.5))).norm(), 5e-3);
  std::printf(
      "[ swingtw  ] cone 0.5: hit at t = %.3f s, max swing %.5f, final %.5f, t > 2 s range "
      "%.3g, twist %.3g, anchor max %.3g m\n",
      t_hit, max_swing, st[0], hi - lo, st[1], anchor);
}

// Thrown with a tumbling spin, the bob stays within the cone and the twist range.
TEST(SwingTwist, ConeAndTwistHoldUnderTumblingSpin) {
  BallJointDef b;
  b.swing_cone_angle = 0.5;
  b.twist_lower = -0.3;
  b.twist_upper = 0.4;
  Pendulum p(b, WorldDef(), Vec3(4.0, 3.0, -5.0));
  double worst_cone = -1e9, worst_twist = -1e9;
  for (int i = 0; i < 3000; ++i) {
    p.w.step(kDt);
    const auto st = p.w.ballSwingTwist(p.joint);
    worst_cone = std::max(worst_cone, st[0] - 0.5);
    worst_twist = std::max({worst_twist, b.twist_lower - st[1], st[1] - b.twist_upper});
  }
  EXPECT_LT(worst_cone, 0.02);
  EXPECT_LT(worst_twist, 0.02);
  EXPECT_LT(p.w.jointAnchorError(p.joint).norm(), 1e-3);
  std::printf("[ swingtw  ] tumbling: worst cone excess %.4f rad, worst twist excess %.4f rad\n",
              worst_cone, worst_twist);
}

// A torque about the twist axis turns the bob freely (theta = tau t^2 / (2 I)) until the twist
// limit, which then holds it; reversed, it holds at the lower limit.
TEST(SwingTwist, TwistLimitsHoldAgainstTorque) {
  BallJointDef b;
  b.swing_cone_angle = 0.5;
  b.twist_lower = -0.3;
  b.twist_upper = 0.4;
  Pendulum p(b, zeroG());
  const double tau = 2.0, I = 0.002;
  double twist_20ms = 0.0, max_twist = -1e9, min_twist = 1e9, max_swing = 0.0;
  for (int i = 0; i < 1000; ++i) {
    p.w.applyTorque(p.bob, Vec3(tau, 0, 0));
    p.w.step(kDt);
    const auto st = p.w.ballSwingTwist(p.joint);
    if (i == 19) twist_20ms = st[1];
    max_twist = std::max(max_twist, st[1]);
    max_swing = std::max(max_swing, st[0]);
  }
  const double held_upper = p.w.ballSwingTwist(p.joint)[1];
  const double w_upper = p.w.bodyState(p.bob).angular_velocity.norm();
  for (int i = 0; i < 1000; ++i) {
    p.w.applyTorque(p.bob, Vec3(-tau, 0, 0));
    p.w.step(kDt);
    const auto st = p.w.ballSwingTwist(p.joint);
    min_twist = std::min(min_twist, st[1]);
    max_swing = std::max(max_swing, st[0]);
  }
  const double held_lower = p.w.ballSwingTwist(p.joint)[1];
  // semi-implicit Euler over n substeps of h: theta_n = a h^2 n (n + 1) / 2 (0.5 a t^2 = 0.2)
  const int n = 20 * p.w.def().solver.substeps;
  const double h = kDt / p.w.def().solver.substeps;
  const double expected_20ms = 0.5 * tau / I * h * h * n * (n + 1);  // limit reached at ~28 ms
  EXPECT_NEAR(twist_20ms, expected_20ms, 0.01 * expected_20ms);
  EXPECT_LT(max_twist - 0.4, 0.01);
  EXPECT_NEAR(held_upper, 0.4, 0.005);
  EXPECT_LT(w_upper, 1e-3);
  EXPECT_LT(-0.3 - min_twist, 0.01);
  EXPECT_NEAR(held_lower, -0.3, 0.005);
  EXPECT_LT(max_swing, 1e-3);
  std::printf(
      "[ swingtw  ] twist(20 ms) %.5f (closed form %.5f); upper: max %.5f held %.5f "
      "(|w| %.2g); lower: min %.5f held %.5f; max swing %.2g\n",
      twist_20ms, expected_20ms, max_twist, held_upper, w_upper, min_twist, held_lower, max_swing);
}
