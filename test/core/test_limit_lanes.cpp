// A joint's angle limits solved in its anchor's float lane (point_row_lanes.inc): the kernel
// against the double parts (part_angle_limit.hpp) for the same state, 4 and 8 lanes give the
// same bits, a record passes over only the limits that apply nothing, and in a world the lanes
// hold a limit's static load and a fast arm as the scalar rows do.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <tuple>
#include <vector>

#include "body.hpp"
#include "joint_test_util.hpp"
#include "lane_bodies.hpp"
#include "lane_width.hpp"
#include "part_angle_limit.hpp"
#include "point_row_test_util.hpp"
#include "point_row_wide.hpp"
#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"
#include "softness.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {

// One block, every lane a ball's three limit rows on bodies 2l and 2l + 1 (anchor parts zero:
// K = 0 there, so only the limit rows move the bodies). Lanes [0, kUsed) have limits; the rest
// have j = 0 and must stay untouched.
constexpr int kUsed = 6;

struct LimitCase {
  std::vector<SolverBody> bodies;
  std::vector<std::array<Vec3, 3>> rows;
  std::vector<std::array<double, 3>> lower_c, upper_c;  // theta - lower, upper - theta
  std::vector<std::array<AngleLimitPart, 3>> parts;
};

LimitCase makeCase(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  LimitCase k;
  k.bodies.resize(2 * kRowBlock);
  for (SolverBody& b : k.bodies) {
    b.w = 3.0 * Vec3(u(rng), u(rng), u(rng));
    b.inv_mass = 0.5 + pos(rng);
    const Vec3 d(1 + 19 * pos(rng), 1 + 19 * pos(rng), 1 + 19 * pos(rng));
    b.inv_inertia = d.asDiagonal();
  }
  k.rows.resize(kRowBlock);
  k.lower_c.resize(kRowBlock);
  k.upper_c.resize(kRowBlock);
  k.parts.resize(kRowBlock);
  for (int l = 0; l < kUsed; ++l)
    for (int r = 0; r < 3; ++r) {
      k.rows[l][r] = Vec3(u(rng), u(rng), u(rng)).normalized();
      // a mix: open, open but closing within the substep, past the lower or the upper bound
      const double theta = 0.01 * u(rng);
      k.lower_c[l][r] = theta + (r == 0 ? 0.0 : 0.004);
      k.upper_c[l][r] = (r == 2 ? 0.0 : 0.005) - theta;
      k.parts[l][r].lower_impulse = pos(rng) < 0.5 ? 0.0 : 0.02 * pos(rng);
      k.parts[l][r].upper_impulse = pos(rng) < 0.5 ? 0.0 : 0.02 * pos(rng);
    }
  return k;
}

PointRowBlock makeBlock(const LimitCase& k) {
  PointRowBlock b{};
  b.angle_rows = 3;
  for (int l = 0; l < kRowBlock; ++l) {
    const SolverBody &A = k.bodies[2 * l], &B = k.bodies[2 * l + 1];
    b.body_a[l] = 2 * l, b.body_b[l] = 2 * l + 1;
    const double ea[6] = {A.inv_inertia(0, 0), A.inv_inertia(1, 1), A.inv_inertia(2, 2), 0, 0, 0};
    const double eb[6] = {B.inv_inertia(0, 0), B.inv_inertia(1, 1), B.inv_inertia(2, 2), 0, 0, 0};
    for (int c = 0; c < 6; ++c) b.ii_a[c][l] = float(ea[c]), b.ii_b[c][l] = float(eb[c]);
    for (int r = 0; r < 3; ++r) {
      const bool used = l < kUsed;
      for (int c = 0; c < 3; ++c) b.angle_j[r][c][l] = used ? float(k.rows[l][r][c]) : 0.0f;
      b.limit_c[r][0][l] = used ? float(k.lower_c[l][r]) : 1.0f;
      b.limit_c[r][1][l] = used ? float(k.upper_c[l][r]) : 1.0f;
      b.limit_impulse[r][0][l] = used ? float(k.parts[l][r].lower_impulse) : 0.0f;
      b.limit_impulse[r][1][l] = used ? float(k.parts[l][r].upper_impulse) : 0.0f;
    }
  }
  return b;
}

// The same in double: AngleAxes' order, each angle's limit warm-started, then solved per sweep.
void runDouble(LimitCase& k) {
  StepContext ctx;
  ctx.h = kLaneH;
  ctx.inv_h = 1.0 / kLaneH;
  ctx.joint_softness = kLaneSoft;
  for (int l = 0; l < kUsed; ++l) {
    SolverBody &A = k.bodies[2 * l], &B = k.bodies[2 * l + 1];
    for (int r = 0; r < 3; ++r) k.parts[l][r].warmStart(A, B, k.rows[l][r]);
    for (const bool use_bias : {true, false})
      for (int r = 0; r < 3; ++r) {
        const Vec3& j = k.rows[l][r];
        const double kk = j.dot((A.inv_inertia + B.inv_inertia) * j);
        // theta - lower = lower_c and upper - theta = upper_c for lower 0, upper sum
        const double theta = k.lower_c[l][r], upper = k.lower_c[l][r] + k.upper_c[l][r];
        k.parts[l][r].solve(A, B, j, kk, theta, 0.0, upper, ctx, use_bias);
      }
  }
}

WorldDef limitDef(int lanes) {
  WorldDef d;
  d.sleep.enabled = false;
  d.solver.lanes = lanes;
  return d;
}

// The arm of joint_test_util.hpp on a hinge about +y at its anchor: gravity turns it to
// +theta, onto the upper limit 0.4.
struct HingeArm {
  World w;
  JointId joint;
  explicit HingeArm(int lanes) : w(limitDef(lanes)) {
    HingeJointDef hj;
    std::tie(hj.body_a, hj.body_b) = addAnchoredArm(w);
    hj.axis = Vec3::UnitY();
    hj.enable_limit = true;
    hj.lower = -0.2;
    hj.upper = 0.4;
    joint = w.createHingeJoint(hj);
  }
};

}  // namespace

// The lanes' limit impulses and angular velocities after a warm start and two sweeps are the
// double parts' to float rounding; lanes without limits stay untouched; 4 and 8 lanes give the
// same bits.
TEST(LimitLanes, KernelMatchesDoubleParts) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    LimitCase d = makeCase(seed);
    const LimitCase before = d;
    const std::vector<SolverBody> start = d.bodies;
    PointRowBlock b4 = makeBlock(d);
    std::vector<SolverBody> f4 = start;
    runLanes(4, b4, f4);
    runDouble(d);
    double worst = 0.0, moved = 0.0;
    for (int l = 0; l < kRowBlock; ++l)
      for (int r = 0; r < 3; ++r) {
        if (l >= kUsed) {
          EXPECT_EQ(b4.limit_impulse[r][0][l], 0.0f);
          EXPECT_EQ(b4.limit_impulse[r][1][l], 0.0f);
          continue;
        }
        const AngleLimitPart& p = d.parts[l][r];
        const AngleLimitPart& p0 = before.parts[l][r];
        worst = std::max({worst, std::abs(b4.limit_impulse[r][0][l] - p.lower_impulse),
                          std::abs(b4.limit_impulse[r][1][l] - p.upper_impulse)});
        moved = std::max({moved, std::abs(p.lower_impulse - p0.lower_impulse),
                          std::abs(p.upper_impulse - p0.upper_impulse)});
      }
    for (size_t i = 0; i < start.size(); ++i) {
      worst = std::max(worst, (f4[i].w - d.bodies[i].w).norm() / (1.0 + d.bodies[i].w.norm()));
      if (i >= 2 * kUsed) {
        EXPECT_EQ(f4[i].w, start[i].w) << "body " << i;
      }
    }
    EXPECT_LT(worst, 2e-5) << "seed " << seed;
    EXPECT_GT(moved, 1e-3) << "the sweeps changed the limit impulses (seed " << seed << ")";
    std::printf("[ kernel   ] seed %u: worst difference to double %.2e\n", seed, worst);
    if (cpuHasAvx2()) expectEightLanesSameBits(makeBlock(makeCase(seed)), start, b4, f4);
  }
}

// Limits far from their bounds in every lane, carrying nothing (the block skips such rows);
// with `closing`, lane 3's second lower row is 1 mm from its bound and closes within the
// substep (rate -3 rad/s along its row against C / h = 0.96 rad/s), so the block must solve it.
LimitCase idleCase(bool closing) {
  LimitCase k = makeCase(4);
  for (int l = 0; l < kUsed; ++l)
    for (int r = 0; r < 3; ++r) {
      k.lower_c[l][r] = k.upper_c[l][r] = 0.5;
      k.parts[l][r] = AngleLimitPart();
    }
  if (closing) {
    k.lower_c[3][1] = 0.001;
    k.bodies[7].w = k.bodies[6].w - 3.0 * k.rows[3][1];
  }
  return k;
}

// Open limits leave the bodies as they were, bit for bit; one row closing within the substep
// among them is solved as the double part solves it, the others still apply nothing.
TEST(LimitLanes, OnlyRowsThatActAreSolved) {
  for (const bool closing : {false, true}) {
    LimitCase d = idleCase(closing);
    const std::vector<SolverBody> start = d.bodies;
    PointRowBlock b4 = makeBlock(d);
    std::vector<SolverBody> f4 = start;
    runLanes(4, b4, f4);
    runDouble(d);
    for (int l = 0; l < kRowBlock; ++l)
      for (int r = 0; r < 3; ++r) {
        const bool acts = closing && l == 3 && r == 1;
        EXPECT_EQ(b4.limit_impulse[r][1][l], 0.0f) << "lane " << l << " row " << r;
        if (!acts) {
          EXPECT_EQ(b4.limit_impulse[r][0][l], 0.0f) << "lane " << l << " row " << r;
          continue;
        }
        const double expected = d.parts[l][r].lower_impulse;
        EXPECT_GT(expected, 1e-4);
        EXPECT_NEAR(b4.limit_impulse[r][0][l], expected, 2e-5 * expected);
      }
    for (size_t i = 0; i < start.size(); ++i) {
      if (closing && (i == 6 || i == 7)) {
        EXPECT_LT((f4[i].w - d.bodies[i].w).norm(), 2e-5 * (1.0 + d.bodies[i].w.norm()));
        EXPECT_NE(f4[i].w, start[i].w) << "body " << i;
      } else {
        EXPECT_EQ(f4[i].w, start[i].w) << "body " << i;
      }
    }
    if (cpuHasAvx2()) expectEightLanesSameBits(makeBlock(idleCase(closing)), start, b4, f4);
  }
}

// The arm rests on its upper limit: the limit alone holds its weight's torque m g d about the
// axis (the effort on B about +y is -m g d), and the angle stays within the slop of the bound,
// at lanes 1 (the scalar rows) and 4 and 8.
TEST(LimitLanes, HingeLimitHoldsTheArmsWeight) {
  for (const int lanes : {1, 4, 8}) {
    HingeArm arm(lanes);
    double max_angle = -1.0;
    for (int i = 0; i < 2000; ++i) {
      arm.w.step(kDt);
      max_angle = std::max(max_angle, arm.w.hingeAngle(arm.joint));
    }
    double e[3];
    ASSERT_EQ(arm.w.jointAxisEfforts(arm.joint, e), 1);
    // the arm at 0.4 rad: gravity's lever is d cos(0.4)
    const double expected = -1.0 * kG * 0.3 * std::cos(arm.w.hingeAngle(arm.joint));
    EXPECT_NEAR(e[0], expected, 1e-3 * std::abs(expected)) << "lanes " << lanes;
    EXPECT_LT(max_angle, 0.4 + 0.01) << "lanes " << lanes;
    EXPECT_NEAR(arm.w.hingeAngle(arm.joint), 0.4, 0.01) << "lanes " << lanes;
    std::printf("[ hinge    ] lanes %d: effort %.5f N m (-m g d cos %.5f), angle %.5f\n", lanes,
                e[0], expected, arm.w.hingeAngle(arm.joint));
  }
}

// Spun fast, the arm crosses most of a range within one step: the lanes' speculative rows stop
// it at every bound as the scalar rows do (test_joint_ball_euler.cpp's bar).
TEST(LimitLanes, EulerLimitsHoldWhenSpunFast) {
  for (const int lanes : {4, 8})
    for (const Vec3& spin : {Vec3(40.0, -30.0, 50.0), Vec3(-120.0, 80.0, 100.0),
                             Vec3(0.0, 150.0, -60.0), Vec3(-40.0, 30.0, -50.0),
                             Vec3(120.0, -80.0, -100.0), Vec3(0.0, -150.0, 60.0)}) {
      LimitedArm arm(limitDef(lanes), spin);
      const double worst = arm.stepWorstExcess(1000);
      EXPECT_LT(worst, 2e-3) << "lanes " << lanes << " spin " << spin.transpose();
      EXPECT_LT(arm.w.jointAnchorError(arm.joint).norm(), 1e-3) << "lanes " << lanes;
      if (lanes == 4)
        std::printf("[ limits   ] spin (%g, %g, %g) rad/s: worst excess %.4f rad\n", spin.x(),
                    spin.y(), spin.z(), worst);
    }
}
