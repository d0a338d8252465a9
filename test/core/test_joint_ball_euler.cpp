// Ball joint with Euler limits: limits held (also when spun fast), the Euler decomposition
// and its rates.
#include <gtest/gtest.h>

#include <cmath>

#include "joint_angles.hpp"
#include "joint_test_util.hpp"
#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

TEST(World, BallJointEulerLimitsHold) {
  LimitedArm arm(WorldDef(), Vec3(3.0, -2.0, 4.0));
  EXPECT_LT(arm.stepWorstExcess(3000), 0.02);
  EXPECT_LT(arm.w.jointAnchorError(arm.joint).norm(), 1e-4);
}

// Spun fast, the arm crosses most of a range within one step (up to 0.2 rad per 1 ms step):
// the limits still catch it within the substep that reaches them. Substeps after the first
// keep the advanced angles of joints whose limits are open (AngleAxes::limitsOpen); this checks
// that a joint turning into a limit within the step is not left on stale angles and rows, and
// that a limit whose two rows are skipped together (part_angle_limit.hpp) is not skipped when
// the arm would cross it within the substep.
TEST(World, BallJointEulerLimitsHoldWhenSpunFast) {
  WorldDef wd;
  wd.sleep.enabled = false;
  // Each spin and its reverse: every axis runs into its lower and its upper limit first.
  for (const Vec3& spin : {Vec3(40.0, -30.0, 50.0), Vec3(-120.0, 80.0, 100.0),
                           Vec3(0.0, 150.0, -60.0), Vec3(-40.0, 30.0, -50.0),
                           Vec3(120.0, -80.0, -100.0), Vec3(0.0, -150.0, 60.0)}) {
    LimitedArm arm(wd, spin);
    const double worst = arm.stepWorstExcess(1000);
    EXPECT_LT(worst, 2e-3) << "spin " << spin.transpose();  // the speculative rows stop it
    EXPECT_LT(arm.w.jointAnchorError(arm.joint).norm(), 1e-3) << "spin " << spin.transpose();
    std::printf("[ limits   ] spin (%g, %g, %g) rad/s: worst excess %.4f rad\n", spin.x(),
                spin.y(), spin.z(), worst);
  }
}

// The Euler decomposition reproduces the rotation, and its Jacobian rows match finite differences.
TEST(JointAngles, EulerRoundTripAndRates) {
  const std::array<Vec3, 3> axes = {Vec3::UnitY(), Vec3::UnitX(), Vec3::UnitZ()};  // det -1
  const EulerBasis basis(axes);
  const Quat fa = quatFromRpy(0.2, -0.4, 1.0);
  const Vec3 t(0.3, -0.7, 1.2);
  auto rot = [&](const Vec3& a) {
    return Quat(Eigen::AngleAxisd(a[0], axes[0]) * Eigen::AngleAxisd(a[1], axes[1]) *
                Eigen::AngleAxisd(a[2], axes[2]));
  };
  const Quat fb = fa * rot(t);
  EXPECT_LT((basis.angles(fa, fb) - t).norm(), 1e-12);
  std::array<Vec3, 3> rows;
  Vec3 t_rows;
  ASSERT_TRUE(basis.angles(fa, fb, t_rows, &rows));
  EXPECT_LT((t_rows - t).norm(), 1e-12);
  const Vec3 wrel(0.3, -0.2, 0.5);  // world relative angular velocity of B
  const double eps = 1e-7;
  const Quat fb2 = (Quat(Eigen::AngleAxisd(eps * wrel.norm(), wrel.normalized())) * fb).normalized();
  const Vec3 rate = (basis.angles(fa, fb2) - t) / eps;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(rows[i].dot(wrel), rate[i], 1e-5);
}
