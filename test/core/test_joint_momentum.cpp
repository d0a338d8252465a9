// Momentum of free joint pairs (fixed, prismatic, swing-twist ball) against a plain ball joint.
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
struct FreePair {
  World w;
  BodyId a, b;
  FreePair() : w(zeroG()) {
    a = addDynamic(w, 3.0, diag(0.03, 0.05, 0.04),
                   Transform(Vec3(0, 0, 0), quatFromRpy(0.2, 0.1, 0)), Vec3(0.05, 0, 0),
                   Vec3(0.5, -0.2, 0.1), Vec3(0.4, -1.0, 2.0));
    b = addDynamic(w, 1.2, diag(0.01, 0.012, 0.008),
                   Transform(Vec3(0.4, 0.1, 0.0), quatFromRpy(-0.3, 0.2, 0.6)), Vec3(0.1, 0, 0.02),
                   Vec3(-1.0, 0.5, 0.3), Vec3(-2.0, 1.5, 0.5));
  }
  Transform jointWorld() const {
    return Transform(Vec3(0.2, 0.05, 0.0), quatFromRpy(0.1, -0.2, 0.3));
  }  // A joint def of any type joining a and b at jointWorld().
  template <class Def>
  Def def() const {
    Def d;
    d.body_a = a;
    d.body_b = b;
    d.frame_a = local(w, a, jointWorld());
    d.frame_b = local(w, b, jointWorld());
    return d;
  }

  // Returns the relative change of the angular momentum.
  double check(const char* name, const JointId j) {
    const Vec3 p0 = w.linearMomentum();
    const Vec3 c0 = Vec3(0.1, 0.2, -0.1);
    const Vec3 L0 = w.angularMomentum(c0);
    double anchor = 0.0;
    for (int i = 0; i < 2000; ++i) {
      w.step(kDt);
      anchor = std::max(anchor, w.jointAnchorError(j).norm());
    }
    const double dp = (w.linearMomentum() - p0).norm() / p0.norm();
    const double dL = (w.angularMomentum(c0) - L0).norm() / L0.norm();
    EXPECT_LT(dp, 1e-9) << name;
    EXPECT_LT(anchor, 1e-3) << name;
    std::printf(
        "[ momentum ] %-24s relative change: linear %.3g, angular %.3g; anchor max %.3g m\n", name,
        dp, dL, anchor);
    return dL;
  }
};
}  // namespace

// Angular momentum is not exact for any joint: impulses change w through the inverse inertia
// frozen at the step start while the bodies rotate within the step (an O(h) drift shared with
// the existing joints). The new joints must not do worse than a plain ball joint on the pair.
double ballBaselineAngularDrift() {
  static const double drift = [] {
    FreePair f;
    return f.check("ball (baseline)", f.w.createBallJoint(f.def<BallJointDef>()));
  }();
  return drift;
}

TEST(JointMomentum, FixedPairConservesMomentum) {
  FreePair f;
  FixedJointDef d = f.def<FixedJointDef>();
  const double dL = f.check("fixed", f.w.createFixedJoint(d));
  EXPECT_LT(dL, 2.0 * ballBaselineAngularDrift());
}

TEST(JointMomentum, PrismaticPairConservesMomentum) {
  FreePair f;
  PrismaticJointDef d = f.def<PrismaticJointDef>();
  d.axis = Vec3(1, 1, 0).normalized();
  d.enable_limit = true;
  d.lower = -0.05;
  d.upper = 0.08;
  d.motor.enabled = true;
  d.motor.target_velocity = 0.3;
  d.motor.max_torque = 2.0;
  const JointId j = f.w.createPrismaticJoint(d);
  const double dL = f.check("prismatic (limit+motor)", j);
  EXPECT_LT(dL, 2.0 * ballBaselineAngularDrift());
  const double x = f.w.prismaticPosition(j);
  EXPECT_GT(x, d.lower - 2e-3);
  EXPECT_LT(x, d.upper + 2e-3);
}

TEST(JointMomentum, SwingTwistBallPairConservesMomentum) {
  FreePair f;
  BallJointDef d = f.def<BallJointDef>();
  d.enable_limits = true;
  d.limit_mode = BallLimitMode::SwingTwist;
  d.swing_cone_angle = 0.3;
  d.twist_lower = -0.2;
  d.twist_upper = 0.2;
  const JointId j = f.w.createBallJoint(d);
  const double dL = f.check("ball swing-twist", j);
  EXPECT_LT(dL, 2.0 * ballBaselineAngularDrift());
  const auto st = f.w.ballSwingTwist(j);
  EXPECT_LT(st[0], 0.3 + 0.02);
  EXPECT_LT(std::abs(st[1]), 0.2 + 0.02);
}
