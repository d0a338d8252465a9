// Position projection of the joint rows after the substeps: sliders, welds, hinge axes,
// limits, and the sweeps that stop when nothing moves.
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

// The other joint rows in the position projection: a slider started 0.04 m past its upper
// limit (kind 0) or 0.04 m off its line (1), a slider (2) and a weld (3) turned 0.2 rad out of
// their locked orientation, a hinge whose axis is tilted 0.2 rad (4). Soft rows too weak to
// matter in one step (joint hertz 1): the sweeps after the substeps bring each back to within
// its slop (joint_slop for lengths, angular_slop for angles) and add no velocity. With the
// slops huge (projection off) the error stays.
TEST(JointProjection, SliderWeldAndHingeAxisComeBackWithoutVelocity) {
  for (const bool on : {true, false}) {
    for (int kind = 0; kind < 5; ++kind) {
      WorldDef d = zeroG();
      d.sleep.enabled = false;
      d.solver.joint_hertz = 1.0;
      if (!on) d.solver.joint_slop = d.solver.angular_slop = 1e9;
      World w(d);
      const BodyId a = addStatic(w);
      const double upper = 0.1, start = kind < 2 ? 0.04 : 0.2;
      Transform pose;
      if (kind == 0) pose.p = Vec3(upper + start, 0, 0);
      if (kind == 1) pose.p = Vec3(0, start, 0);
      const Vec3 turn_axis = kind == 4 ? Vec3::UnitX() : Vec3::UnitZ();
      if (kind >= 2) pose.q = Quat(Eigen::AngleAxisd(start, turn_axis));
      const BodyId b = addDynamic(w, 1.0, diag(0.02, 0.02, 0.005), pose);
      if (kind <= 2) {
        PrismaticJointDef p;
        p.body_a = a, p.body_b = b;
        p.axis = Vec3::UnitX();
        p.enable_limit = true;
        p.lower = -upper, p.upper = upper;
        w.createPrismaticJoint(p);
      } else if (kind == 3) {
        FixedJointDef f;
        f.body_a = a, f.body_b = b;
        w.createFixedJoint(f);
      } else {
        HingeJointDef h;
        h.body_a = a, h.body_b = b;
        h.axis = Vec3::UnitZ();
        w.createHingeJoint(h);
      }
      const auto error = [&]() {
        const Transform x = w.bodyPose(b);
        if (kind == 0) return x.p.x() - upper;
        if (kind == 1) return x.p.tail<2>().norm();
        if (kind == 4) return std::acos(std::clamp((x.q * Vec3::UnitZ()).z(), -1.0, 1.0));
        return x.q.angularDistance(Quat::Identity());
      };
      ASSERT_NEAR(error(), start, 1e-9) << "kind " << kind;
      w.step(kDt);
      const double slop = kind < 2 ? d.solver.joint_slop : d.solver.angular_slop;
      const BodyState st = w.bodyState(b);
      if (on) {
        EXPECT_LT(error(), slop + 0.05 * slop) << "kind " << kind;
        EXPECT_GT(error(), 0.5 * slop) << "kind " << kind;  // the slop is left to the soft rows
      } else {
        EXPECT_GT(error(), 0.95 * start) << "kind " << kind;
      }
      EXPECT_LT(st.linear_velocity.norm(), 0.01) << "kind " << kind;
      EXPECT_LT(st.angular_velocity.norm(), 0.1) << "kind " << kind;  // a soft 1 Hz row's push
      std::printf("[ jproj    ] kind %d projection %s: error %.3g -> %.4g, |v| %.2g, |w| %.2g\n",
                  kind, on ? "on" : "off", start, error(), st.linear_velocity.norm(),
                  st.angular_velocity.norm());
    }
  }
}

namespace {
// A ball joint limited to Euler angles in [-1, 1] x [-1, 0] x [-1, 1] about x, y, z (euler),
// or to a swing cone of 0.3 rad and a twist range [-1, twist_upper] (the projection tests).
BallJointDef limitedBall(BodyId a, BodyId b, bool euler, double twist_upper) {
  BallJointDef bj;
  bj.body_a = a, bj.body_b = b;
  bj.enable_limits = true;
  if (euler) {
    bj.axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
    bj.lower = {-1, -1, -1};
    bj.upper = {1, 0, 1};
  } else {
    bj.limit_mode = BallLimitMode::SwingTwist;
    bj.swing_cone_angle = 0.3;
    bj.twist_lower = -1.0, bj.twist_upper = twist_upper;
  }
  return bj;
}
}  // namespace

// The position sweeps stop at the first one that moves no body (world.cpp, solveIsland): that
// is exact only if every projection says when it moved one. Each case starts at 2.5 times the
// most one sweep corrects (max_position_correction 0.05 m, max_angular_correction 0.2 rad), so
// the second and third sweeps have work left: with 3 sweeps the error must end well below what
// 1 sweep leaves. A projection that moved a body but said it did not would end the sweeps
// after the first, and leave the error of 1 sweep. Cases: 0 slider limit, 1 slider line, 2
// weld (rotation lock), 3 hinge axis, 4 hinge limit, 5 ball Euler limit, 6 swing cone, 7 twist
// range, 8 ball anchor, 9 sphere in the ground. Soft rows too weak to matter (joint hertz 1),
// and the exact anchors (joint_tree.hpp) off: they would close case 8 after any sweep.
TEST(PositionSweeps, EachProjectionThatMovesABodyLetsTheNextSweepRun) {
  constexpr double kLinear = 0.12, kAngular = 0.5;
  for (int kind = 0; kind < 10; ++kind) {
    double error_after[2] = {0, 0};
    for (const int sweeps : {1, 3}) {
      WorldDef d = zeroG();
      d.sleep.enabled = false;
      d.solver.joint_hertz = 1.0;
      d.solver.position_iterations = sweeps;
      d.solver.anchor_iterations = 0;
      d.solver.exact_joints = false;
      World w(d);
      const BodyId a = kind == 9 ? addGround(w) : addStatic(w);
      const bool linear = kind <= 1 || kind >= 8;
      // turned about: the hinge axis tilted about x, the Euler limit and the swing about y, the
      // twist about x (the twist axis)
      const Vec3 axis = kind == 5 || kind == 6   ? Vec3::UnitY()
                        : kind == 3 || kind == 7 ? Vec3::UnitX()
                                                 : Vec3::UnitZ();
      Transform pose;
      if (kind == 0) pose.p = Vec3(0.1 + kLinear, 0, 0);  // slider range [-0.1, 0.1]
      if (kind == 1) pose.p = Vec3(0, kLinear, 0);
      if (kind == 8) pose.p = Vec3(kLinear, 0, 0);
      if (kind == 9) pose.p = Vec3(0, 0, 0.1 - kLinear);  // sphere of radius 0.1
      if (!linear) pose.q = Quat(Eigen::AngleAxisd(kind == 6 ? 0.3 + kAngular : kAngular, axis));
      const BodyId b = kind == 9 ? addSphere(w, 0.1, 1.0, pose.p)
                                 : addDynamic(w, 1.0, diag(0.02, 0.02, 0.005), pose);
      JointId j;
      if (kind <= 1) {
        PrismaticJointDef p;
        p.body_a = a, p.body_b = b;
        p.axis = Vec3::UnitX();
        p.enable_limit = true;
        p.lower = -0.1, p.upper = 0.1;
        j = w.createPrismaticJoint(p);
      } else if (kind == 2) {
        FixedJointDef f;
        f.body_a = a, f.body_b = b;
        j = w.createFixedJoint(f);
      } else if (kind == 3 || kind == 4) {
        HingeJointDef h;
        h.body_a = a, h.body_b = b;
        h.axis = Vec3::UnitZ();
        h.enable_limit = kind == 4;
        h.lower = -1.0, h.upper = 0.0;
        j = w.createHingeJoint(h);
      } else if (kind <= 8) {
        BallJointDef bj = limitedBall(a, b, kind == 5, kind == 6 ? 1.0 : 0.0);
        bj.enable_limits = kind != 8;
        j = w.createBallJoint(bj);
      }
      const auto error = [&]() {
        const Transform x = w.bodyPose(b);
        switch (kind) {
          case 0: return x.p.x() - 0.1;
          case 1: return x.p.tail<2>().norm();
          case 2: return x.q.angularDistance(Quat::Identity());
          case 3: return std::acos(std::clamp((x.q * Vec3::UnitZ()).z(), -1.0, 1.0));
          case 4: return w.hingeAngle(j);
          case 5: return w.ballAngles(j)[1];
          case 6: return w.ballSwingTwist(j)[0] - 0.3;
          case 7: return w.ballSwingTwist(j)[1];
          case 8: return w.jointAnchorError(j).norm();
          default: return 0.1 - x.p.z();  // depth
        }
      };
      ASSERT_NEAR(error(), linear ? kLinear : kAngular, 1e-9) << "kind " << kind;
      w.step(kDt);
      error_after[sweeps == 3] = error();
    }
    const double start = kind <= 1 || kind >= 8 ? kLinear : kAngular;
    EXPECT_GT(error_after[0], 0.4 * start) << "kind " << kind;  // one sweep is not enough
    EXPECT_LT(error_after[1], 0.5 * error_after[0]) << "kind " << kind;
    std::printf("[ sweeps   ] kind %d: error %.3g -> %.4g after 1 sweep, %.4g after 3\n", kind,
                start, error_after[0], error_after[1]);
  }
}

// Within a sweep, a projection is skipped when it moved nothing at its last look and none of its
// bodies has moved since (unchangedSince, solver_context.hpp): a move must mark the bodies.
// A chain static A - B - C, all anchors at the bodies' centres: B starts 0.12 m from A's anchor,
// C on B's. The B-C joint is projected first and finds nothing; then A-B pulls B 0.05 m (the
// most one sweep moves), which opens B-C. Only the next sweeps' look at B-C moves C: with
// three sweeps C comes 0.05 m off its start and B-C ends 0.05 m open; were B left unmarked, B-C
// would be skipped, C would stay and B-C would end 0.1 m open.
TEST(PositionSweeps, AMovedBodyMakesItsOtherJointsLookAgain) {
  WorldDef d = zeroG();
  d.sleep.enabled = false;
  d.solver.joint_hertz = 1.0;
  d.solver.anchor_iterations = 0;
  World w(d);
  const BodyId a = addStatic(w);
  const Vec3 start(0.12, 0, 0);
  const BodyId b = addDynamic(w, 1.0, diag(0.02, 0.02, 0.02), Transform(start, Quat::Identity()));
  const BodyId c = addDynamic(w, 1.0, diag(0.02, 0.02, 0.02), Transform(start, Quat::Identity()));
  BallJointDef bc;
  bc.body_a = b, bc.body_b = c;
  const JointId j_bc = w.createBallJoint(bc);  // created (and swept) first
  BallJointDef ab;
  ab.body_a = a, ab.body_b = b;
  const JointId j_ab = w.createBallJoint(ab);
  ASSERT_NEAR(w.jointAnchorError(j_ab).norm(), 0.12, 1e-9);  // positions sit on a grid
  ASSERT_LT(w.jointAnchorError(j_bc).norm(), 1e-9);
  w.step(kDt);
  const double moved_c = (start - w.bodyPose(c).p).norm();
  const double bc_error = w.jointAnchorError(j_bc).norm();
  std::printf("[ sweeps   ] chain: C moved %.4g m, anchor errors A-B %.4g, B-C %.4g m\n", moved_c,
              w.jointAnchorError(j_ab).norm(), bc_error);
  EXPECT_GT(moved_c, 0.04);
  EXPECT_LT(bc_error, 0.07);
}

// ---------------------------------------------------------------- position projection of limits

// A body started 0.2 rad past a limit, with soft rows too weak to matter in one step (joint
// hertz 1): the position sweeps after the substeps turn it back to within angular_slop, and add
// no velocity. With the projection off (angular_slop huge) the violation stays at ~0.2 rad.
// Each case: hinge (upper 0), ball with Euler limits (t1 upper 0), ball with a swing cone
// (0.3) and a twist range (upper 0).
TEST(LimitProjection, TurnsAViolatedLimitBackWithoutAddingVelocity) {
  for (const double slop : {SolverSettings().angular_slop, 1e9}) {
    for (int kind = 0; kind < 4; ++kind) {
      WorldDef d = zeroG();
      d.sleep.enabled = false;
      d.solver.joint_hertz = 1.0;
      d.solver.angular_slop = slop;
      World w(d);
      const BodyId a = addStatic(w);
      // B's COM sits on the anchor, so turning it keeps the anchor together.
      const Vec3 axis = kind == 0 ? Vec3::UnitZ() : (kind == 1 ? Vec3::UnitY() : Vec3::UnitX());
      const double start = kind == 2 ? 0.5 : 0.2;  // swing 0.5 against a cone of 0.3
      const Quat q(Eigen::AngleAxisd(start, kind == 2 ? Vec3::UnitY() : axis));
      const BodyId b = addDynamic(w, 1.0, diag(0.02, 0.02, 0.005), Transform(Vec3::Zero(), q));
      JointId j;
      if (kind == 0) {
        HingeJointDef h;
        h.body_a = a, h.body_b = b;
        h.axis = axis;
        h.enable_limit = true;
        h.lower = -1.0, h.upper = 0.0;
        j = w.createHingeJoint(h);
      } else {
        j = w.createBallJoint(limitedBall(a, b, kind == 1, kind == 2 ? 1.0 : 0.0));
      }
      const auto violation = [&]() {
        if (kind == 0) return w.hingeAngle(j) - 0.0;
        if (kind == 1) return w.ballAngles(j)[1] - 0.0;
        const auto st = w.ballSwingTwist(j);
        return kind == 2 ? st[0] - 0.3 : st[1] - 0.0;
      };
      ASSERT_NEAR(violation(), 0.2, 1e-9) << "kind " << kind;
      w.step(kDt);
      const double omega = w.bodyState(b).angular_velocity.norm();
      if (slop < 1.0) {
        EXPECT_LT(violation(), slop + 1e-3) << "kind " << kind;
        EXPECT_GT(violation(), 0.0) << "kind " << kind;  // the slop is left to the soft rows
      } else {
        EXPECT_GT(violation(), 0.19) << "kind " << kind;
      }
      EXPECT_LT(omega, 0.1) << "kind " << kind;  // a soft 1 Hz row's push, no more
      EXPECT_LT(w.jointAnchorError(j).norm(), 1e-9) << "kind " << kind;
      std::printf("[ limproj  ] kind %d slop %g: violation %.3g -> %.4g rad, |w| %.3g rad/s\n",
                  kind, slop, 0.2, violation(), omega);
    }
  }
}
