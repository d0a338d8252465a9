// Ball joint with an elliptical swing cone: each half-angle holds about its own swing axis, the
// boundary holds in between, and equal half-angles are the circular cone exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "joint_test_util.hpp"
#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {

constexpr double kConeY = 0.8, kConeZ = 0.4;  // half-angles about the joint's y and z axes

// A 1 kg bob on a ball joint at the origin, its COM 0.5 m along the twist axis x.
struct ConePendulum {
  World w;
  BodyId bob;
  JointId joint;
  ConePendulum(double cone_y, double cone_z, const WorldDef& def, const Vec3& omega = Vec3::Zero())
      : w(def) {
    const BodyId base = addStatic(w);
    bob = addDynamic(w, 1.0, diag(0.002, 0.02, 0.02), Transform(), Vec3(0.5, 0, 0), Vec3::Zero(),
                     omega);
    BallJointDef b;
    b.body_a = base;
    b.body_b = bob;
    b.enable_limits = true;
    b.limit_mode = BallLimitMode::SwingTwist;
    b.swing_cone_angle = cone_y;
    b.swing_cone_angle_2 = cone_z;
    b.twist_lower = -0.3;
    b.twist_upper = 0.3;
    joint = w.createBallJoint(b);
  }
  // Swing rotation vector (joint frame = world here): its y and z components.
  Vec3 swingVector() const {
    const Vec3 t = (w.comPosition(bob)).normalized();
    const Vec3 c = Vec3::UnitX().cross(t);
    if (c.norm() < 1e-12) return Vec3::Zero();
    return std::atan2(c.norm(), t.x()) * c.normalized();
  }
  double ellipse() const {  // (sw_y / a)^2 + (sw_z / b)^2: 1 on the cone
    const Vec3 s = swingVector();
    return std::pow(s.y() / kConeY, 2) + std::pow(s.z() / kConeZ, 2);
  }
};

// Pushes the bob with a constant torque about `axis` for 1 s; returns the held swing vector.
Vec3 pushAgainstCone(const Vec3& axis, double* max_swing, double* anchor) {
  ConePendulum p(kConeY, kConeZ, zeroG());
  *max_swing = 0.0;
  *anchor = 0.0;
  for (int i = 0; i < 1000; ++i) {
    p.w.applyTorque(p.bob, 2.0 * axis);
    p.w.step(kDt);
    *max_swing = std::max(*max_swing, p.w.ballSwingTwist(p.joint)[0]);
    *anchor = std::max(*anchor, p.w.jointAnchorError(p.joint).norm());
  }
  return p.swingVector();
}

}  // namespace

// Driven about y the bob stops at the y half-angle, driven about z at the z half-angle.
TEST(BallCone, EachHalfAngleStopsItsAxis) {
  double max_y, max_z, anchor_y, anchor_z;
  const Vec3 sy = pushAgainstCone(Vec3::UnitY(), &max_y, &anchor_y);
  const Vec3 sz = pushAgainstCone(Vec3::UnitZ(), &max_z, &anchor_z);
  EXPECT_NEAR(sy.y(), kConeY, 0.01);
  EXPECT_NEAR(sy.z(), 0.0, 0.01);
  EXPECT_NEAR(sz.z(), kConeZ, 0.01);
  EXPECT_NEAR(sz.y(), 0.0, 0.01);
  EXPECT_LT(max_y - kConeY, 0.02);
  EXPECT_LT(max_z - kConeZ, 0.02);
  EXPECT_LT(std::max(anchor_y, anchor_z), 1e-3);
  std::printf("[ cone     ] about y: held %.5f (half-angle %.2f, max %.5f); about z: held %.5f "
              "(half-angle %.2f, max %.5f); anchor max %.2g m\n",
              sy.y(), kConeY, max_y, sz.z(), kConeZ, max_z, std::max(anchor_y, anchor_z));
}

// Pushed between the axes the bob slides along the ellipse (no friction) pressed onto it, and a
// tumbling spin never leaves it.
TEST(BallCone, BoundaryHoldsBetweenTheAxes) {
  ConePendulum p(kConeY, kConeZ, zeroG());
  const Vec3 axis = Vec3(0, 1, 1).normalized();
  double pressed_max = 0.0, pressed_sum = 0.0;
  int pressed_n = 0;
  for (int i = 0; i < 3000; ++i) {
    p.w.applyTorque(p.bob, 2.0 * axis);
    p.w.step(kDt);
    if (i < 1000) continue;
    pressed_max = std::max(pressed_max, p.ellipse());
    pressed_sum += p.ellipse();
    ++pressed_n;
  }
  const double pressed_mean = pressed_sum / pressed_n;
  EXPECT_LT(pressed_max, 1.02);
  EXPECT_GT(pressed_mean, 0.97);
  ConePendulum spin(kConeY, kConeZ, WorldDef(), Vec3(4.0, 3.0, -5.0));
  double worst = 0.0;
  for (int i = 0; i < 3000; ++i) {
    spin.w.step(kDt);
    worst = std::max(worst, spin.ellipse());
  }
  EXPECT_LT(worst, 1.05);
  std::printf("[ cone     ] pressed diagonally (1-3 s): ellipse max %.4f, mean %.4f (1 = on the "
              "cone); tumbling: worst %.4f\n", pressed_max, pressed_mean, worst);
}

// Equal half-angles are the circular cone, step for step.
TEST(BallCone, EqualHalfAnglesAreTheCircularCone) {
  ConePendulum circ(0.5, 0.0, WorldDef(), Vec3(4.0, 3.0, -5.0));
  ConePendulum same(0.5, 0.5, WorldDef(), Vec3(4.0, 3.0, -5.0));
  for (int i = 0; i < 1000; ++i) {
    circ.w.step(kDt);
    same.w.step(kDt);
  }
  EXPECT_EQ(circ.w.comPosition(circ.bob), same.w.comPosition(same.bob));
  EXPECT_EQ(circ.w.ballSwingTwist(circ.joint), same.w.ballSwingTwist(same.joint));
}
