// Prismatic joint: g sin(theta) on an inclined slider, limit, motors, breaking load.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "joint_test_util.hpp"
#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
// A slider on a static rail inclined at theta, the axis pointing downhill; the slider's COM
// hangs 0.1 m below the rail, so the rotation lock and the off-axis rows carry a couple.
struct Incline {
  World w;
  BodyId rail, slider;
  JointId joint;
  double theta;
  Incline(double theta_, const PrismaticJointDef& extra, const WorldDef& def = WorldDef())
      : w(def), theta(theta_) {
    rail = addStatic(w);
    slider = addDynamic(w, 3.0, diag(0.01, 0.02, 0.015), Transform(Vec3(0, 0, 1), Quat::Identity()),
                        Vec3(0, 0, -0.1));
    PrismaticJointDef p = extra;
    p.body_a = rail;
    p.body_b = slider;
    p.frame_a = Transform(Vec3(0, 0, 1), Quat(Eigen::AngleAxisd(theta, Vec3::UnitY())));
    p.frame_b = Transform(Vec3::Zero(), p.frame_a.q);
    p.axis = Vec3::UnitX();  // R_y(theta) x = (cos theta, 0, -sin theta): downhill
    joint = w.createPrismaticJoint(p);
  }
  double rotationError() const { return angleBetween(w.bodyPose(slider).q, Quat::Identity()); }
};
}  // namespace

TEST(PrismaticJoint, InclinedSlideAcceleratesAtGSinTheta) {
  const double theta = M_PI / 6;
  Incline s(theta, PrismaticJointDef());
  EXPECT_EQ(s.w.jointType(s.joint), JointType::Prismatic);
  double drift = 0.0, rot = 0.0;
  for (int i = 0; i < 1000; ++i) {
    s.w.step(kDt);
    drift = std::max(drift, s.w.jointAnchorError(s.joint).norm());
    rot = std::max(rot, s.rotationError());
  }
  const double a = kG * std::sin(theta);
  const Vec3 axis(std::cos(theta), 0, -std::sin(theta));
  const double v = s.w.bodyState(s.slider).linear_velocity.dot(axis);
  const double x = s.w.prismaticPosition(s.joint);
  EXPECT_NEAR(v / 1.0, a, 0.01 * a);
  EXPECT_NEAR(2.0 * x / (1.0 * 1.0), a, 0.01 * a);
  EXPECT_LT(drift, 1e-3);
  EXPECT_LT(rot, 1e-3);
  std::printf(
      "[ slider   ] t = 1 s: a from v %.5f, from x %.5f (g sin theta = %.5f), off-axis "
      "drift max %.3g m, rotation max %.3g rad\n",
      v, 2.0 * x, a, drift, rot);
}

TEST(PrismaticJoint, LimitStopsSlideAtUpper) {
  PrismaticJointDef p;
  p.enable_limit = true;
  p.lower = -1.0;
  p.upper = 0.5;
  Incline s(M_PI / 6, p, noSleep());
  double max_x = -1e9, drift = 0.0, lo = 1e9, hi = -1e9;
  for (int i = 0; i < 3000; ++i) {
    s.w.step(kDt);
    const double x = s.w.prismaticPosition(s.joint);
    max_x = std::max(max_x, x);
    drift = std::max(drift, s.w.jointAnchorError(s.joint).norm());
    if (s.w.time() > 2.0) {
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
  const double x = s.w.prismaticPosition(s.joint);
  EXPECT_LT(max_x - p.upper, 2e-3);
  EXPECT_NEAR(x, p.upper, 2e-3);
  EXPECT_LT(hi - lo, 1e-3);
  EXPECT_LT(drift, 1e-3);
  // resting on the limit, the joint carries the weight: |F| = m g
  EXPECT_NEAR(s.w.jointForce(s.joint), 3.0 * kG, 0.01 * 3.0 * kG);
  std::printf(
      "[ slider   ] limit 0.5 m: max %.6f m, final %.6f m, t > 2 s range %.3g m, off-axis "
      "drift max %.3g m, force %.3f N (m g %.3f N)\n",
      max_x, x, hi - lo, drift, s.w.jointForce(s.joint), 3.0 * kG);
}

// Horizontal rail, gravity across the axis: the velocity motor accelerates at its force cap
// F / m until it reaches the target speed.
TEST(PrismaticJoint, VelocityMotorReachesTargetSpeed) {
  PrismaticJointDef p;
  p.motor.enabled = true;
  p.motor.target_velocity = 1.5;
  p.motor.max_torque = 6.0;  // N on 3 kg: 2 m/s^2, target reached at t = 0.75 s
  Incline s(0.0, p);
  double drift = 0.0, v_quarter = 0.0;
  for (int i = 0; i < 1500; ++i) {
    s.w.step(kDt);
    drift = std::max(drift, s.w.jointAnchorError(s.joint).norm());
    if (i == 249) v_quarter = s.w.bodyState(s.slider).linear_velocity.x();
  }
  const double v = s.w.bodyState(s.slider).linear_velocity.x();
  EXPECT_NEAR(v_quarter, 0.5, 0.005);
  EXPECT_NEAR(v, 1.5, 1e-4);
  EXPECT_LT(drift, 1e-3);
  std::printf(
      "[ slider   ] motor: v(0.25 s) %.5f m/s (F/m t = 0.5), v(1.5 s) %.7f m/s (target "
      "1.5), off-axis drift max %.3g m\n",
      v_quarter, v, drift);
}

TEST(PrismaticJoint, PositionMotorReachesTarget) {
  PrismaticJointDef p;
  p.motor.enabled = true;
  p.motor.target = 0.2;
  p.motor.hertz = 4.0;
  p.motor.damping_ratio = 1.0;
  p.motor.max_torque = 100.0;
  Incline s(0.0, p, zeroG());
  for (int i = 0; i < 3000; ++i) s.w.step(kDt);
  const double x = s.w.prismaticPosition(s.joint);
  EXPECT_NEAR(x, 0.2, 1e-4);
  std::printf("[ slider   ] position motor: x(3 s) %.6f m (target 0.2)\n", x);
}

// Horizontal rail, gravity across the axis: a breakable slider breaks iff m g passes its limit.
TEST(PrismaticJoint, BreaksIffLoadPassesLimit) {
  const double weight = 3.0 * kG;
  for (const double factor : {0.95, 1.05}) {
    PrismaticJointDef p;
    p.spring.break_force = factor * weight;
    Incline s(0.0, p);
    double max_force = 0.0;
    for (int i = 0; i < 1000 && !s.w.isJointBroken(s.joint); ++i) {
      s.w.step(kDt);
      if (!s.w.isJointBroken(s.joint)) max_force = std::max(max_force, s.w.jointForce(s.joint));
    }
    EXPECT_EQ(s.w.isJointBroken(s.joint), factor < 1.0) << "factor " << factor;
    if (factor > 1.0) {
      EXPECT_NEAR(max_force, weight, 1e-3 * weight);
      std::printf("[ slider   ] break_force %.2f m g: held 1 s, max force %.4f N (m g %.4f N)\n",
                  factor, max_force, weight);
    } else {
      std::printf("[ slider   ] break_force %.2f m g: broke at t = %.4f s\n", factor, s.w.time());
    }
  }
}
