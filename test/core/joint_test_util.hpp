// Helpers shared by the joint tests (test_joint_*.cpp).
#pragma once

#include <algorithm>
#include <limits>
#include <tuple>
#include <utility>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

namespace ragdoll_sim {
namespace test {

inline constexpr double kDt = 1e-3;
inline constexpr double kG = 9.81;

inline Mat3 diag(double x, double y, double z) { return Vec3(x, y, z).asDiagonal(); }

// Pulls bob down with F = k t at its COM until the joint breaks (at most 2 s): the break time
// (-1 if none) and the last reading of `load` while the joint held.
template <class Load>
std::pair<double, double> pullUntilBroken(World& w, BodyId bob, JointId j, double k, Load load) {
  double broke_at = -1.0, last = 0.0;
  for (int i = 0; i < 2000 && broke_at < 0; ++i) {
    w.applyForce(bob, Vec3(0, 0, -k * w.time()), w.comPosition(bob));
    w.step(kDt);
    if (w.isJointBroken(j))
      broke_at = w.time();
    else
      last = load();
  }
  return {broke_at, last};
}

inline double angleBetween(const Quat& a, const Quat& b) { return a.angularDistance(b); }

inline WorldDef zeroG() {
  WorldDef d;
  d.gravity.setZero();
  return d;
}

// Settling is measured on the solver alone: a body that went to sleep would hold still anyway.
inline WorldDef noSleep() {
  WorldDef d;
  d.sleep.enabled = false;
  return d;
}

// The frame of the joint in each body's link frame, given its world pose at creation.
inline Transform local(const World& w, BodyId b, const Transform& world_frame) {
  return w.bodyPose(b).inverse() * world_frame;
}

inline BodyId addAnchor(World& w) {
  BodyDef d;
  d.type = BodyType::Static;
  return w.createBody(d);
}

inline BodyId addBall(World& w, double mass, const Vec3& pos) {
  BodyDef d;
  d.pose.p = pos;
  d.mass = mass;
  d.inertia = Mat3::Identity() * 0.01 * mass;
  return w.createBody(d);
}

// A static anchor and an arm (1 kg, COM 0.3 m out along x, inertia 0.01) at the origin,
// started spinning at `spin`: {anchor, arm}.
inline std::pair<BodyId, BodyId> addAnchoredArm(World& w, const Vec3& spin = Vec3::Zero()) {
  BodyDef anchor_def;
  anchor_def.type = BodyType::Static;
  BodyDef arm;
  arm.mass = 1.0;
  arm.com = Vec3(0.3, 0.0, 0.0);
  arm.inertia = Mat3::Identity() * 0.01;
  arm.angular_velocity = spin;
  const BodyId anchor = w.createBody(anchor_def);
  return {anchor, w.createBody(arm)};
}

// The arm on its anchor through a ball joint with Euler limits (y-x-z, as a URDF chain),
// started spinning at `spin`; steps it and returns the worst excess of an angle over its range.
struct LimitedArm {
  World w;
  BallJointDef bj;
  JointId joint;
  LimitedArm(const WorldDef& wd, const Vec3& spin) : w(wd) {
    std::tie(bj.body_a, bj.body_b) = addAnchoredArm(w, spin);
    bj.axes = {Vec3::UnitY(), Vec3::UnitX(), Vec3::UnitZ()};
    bj.enable_limits = true;
    bj.lower = {-0.5, -0.3, -0.4};
    bj.upper = {0.6, 0.3, 0.2};
    joint = w.createBallJoint(bj);
  }
  double stepWorstExcess(int steps) {
    double worst = 0.0;
    for (int i = 0; i < steps; ++i) {
      w.step(kDt);
      const auto t = w.ballAngles(joint);
      for (int k = 0; k < 3; ++k)
        worst = std::max({worst, bj.lower[k] - t[k], t[k] - bj.upper[k]});
    }
    return worst;
  }
};

}  // namespace test
}  // namespace ragdoll_sim
