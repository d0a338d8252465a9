// The joint anchors in float lanes (point_lanes.hpp): 4 and 8 lanes give the same bits on one
// and two threads, and the lanes keep the closed forms (pendulum period, a hanging chain's
// joint forces) and the anchors together.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "joint_test_util.hpp"
#include "lane_width.hpp"
#include "ragdoll_sim/state_hash.hpp"
#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {

// exact: the joint trees' exact anchors and the position sweeps after the velocity sweeps (off:
// the lanes alone hold the anchors).
WorldDef wideDef(int lanes, int threads, bool exact = true) {
  WorldDef d;
  d.solver.exact_joints = exact;
  if (!exact) d.solver.position_iterations = d.solver.anchor_iterations = 0;
  d.sleep.enabled = false;
  d.solver.lanes = lanes;
  d.threads = threads;
  return d;
}

// Box links joined at `anchor` (world): ball, hinge (about y, limited) or fixed.
enum class Kind { Ball, Hinge, Fixed };
void join(World& w, Kind kind, BodyId a, BodyId b, const Vec3& anchor) {
  const Transform f(anchor, Quat::Identity());
  if (kind == Kind::Ball) {
    BallJointDef j;
    j.body_a = a, j.body_b = b, j.frame_a = local(w, a, f), j.frame_b = local(w, b, f);
    w.createBallJoint(j);
  } else if (kind == Kind::Hinge) {
    HingeJointDef j;
    j.body_a = a, j.body_b = b, j.frame_a = local(w, a, f), j.frame_b = local(w, b, f);
    j.axis = Vec3::UnitY();
    j.enable_limit = true;
    j.lower = -2.0, j.upper = 0.1;
    w.createHingeJoint(j);
  } else {
    FixedJointDef j;
    j.body_a = a, j.body_b = b, j.frame_a = local(w, a, f), j.frame_b = local(w, b, f);
    w.createFixedJoint(j);
  }
}

// A humanoid of boxes at `base` (pelvis height 1 m above it), falling with a push and a spin:
// ball joints at shoulders and hips, limited hinges at elbows and knees, a fixed neck.
void addRagdoll(World& w, const Vec3& base, const Vec3& v, const Vec3& omega) {
  const auto box = [&](const Vec3& half, double m, const Vec3& p) {
    return addBody(w, Geometry::box(half), m, boxInertia(half, m), Transform(base + p, Quat::Identity()),
                   Material(), v);
  };
  const Vec3 torso_half(0.1, 0.15, 0.25);
  const BodyId torso = addDynamic(w, 30.0, boxInertia(torso_half, 30.0),
                                  Transform(base + Vec3(0, 0, 1.25), Quat::Identity()),
                                  Vec3::Zero(), v, omega);
  w.addShape(torso, {Geometry::box(torso_half), Transform(), Material()});
  const BodyId head = box(Vec3(0.09, 0.09, 0.1), 5.0, Vec3(0, 0, 1.62));
  join(w, Kind::Fixed, torso, head, base + Vec3(0, 0, 1.51));
  for (const double s : {-1.0, 1.0}) {
    const BodyId upper = box(Vec3(0.14, 0.04, 0.04), 2.0, Vec3(0, s * 0.35, 1.45));
    join(w, Kind::Ball, torso, upper, base + Vec3(0, s * 0.2, 1.45));
    const BodyId fore = box(Vec3(0.12, 0.035, 0.035), 1.2, Vec3(0, s * 0.62, 1.45));
    join(w, Kind::Hinge, upper, fore, base + Vec3(0, s * 0.49, 1.45));
    const BodyId thigh = box(Vec3(0.06, 0.06, 0.2), 8.0, Vec3(0, s * 0.09, 0.78));
    join(w, Kind::Ball, torso, thigh, base + Vec3(0, s * 0.09, 0.99));
    const BodyId shin = box(Vec3(0.05, 0.05, 0.2), 4.0, Vec3(0, s * 0.09, 0.35));
    join(w, Kind::Hinge, thigh, shin, base + Vec3(0, s * 0.09, 0.56));
  }
}

// Two ragdolls falling onto the ground and a swinging chain, stepped `steps` times.
uint64_t sceneHash(int lanes, int threads, int steps) {
  World w(wideDef(lanes, threads));
  addGround(w);
  addRagdoll(w, Vec3(0, 0, 0.3), Vec3(0.5, 0, 0), Vec3(1.0, 2.0, 0.5));
  addRagdoll(w, Vec3(2.0, 0, 0.1), Vec3(-0.3, 0.2, 0), Vec3(-2.0, 0.5, 1.0));
  addChain(w, Vec3(-2.0, 0, 3.5), std::vector<double>(8, 1.0));
  for (int i = 0; i < steps; ++i) w.step(1.0 / 240.0);
  return hashStates(w);
}

}  // namespace

// 4 and 8 lanes: the same state bit for bit, on one thread and on two; and not the scalar path.
TEST(WidePoints, SameBitsAtFourAndEightLanesAndAnyThreads) {
  const int steps = 400;
  const uint64_t h4 = sceneHash(4, 1, steps);
  EXPECT_EQ(h4, sceneHash(8, 1, steps));
  EXPECT_EQ(h4, sceneHash(4, 2, steps));
  EXPECT_EQ(h4, sceneHash(8, 2, steps));
  EXPECT_NE(h4, sceneHash(1, 1, steps)) << "the lanes took no anchor";
  std::printf("[ wide     ] hash %016llx (avx2 %d)\n", (unsigned long long)h4, int(cpuHasAvx2()));
}

// A bob on a ball joint (point mass, L = 1 m) swings with the small-angle period
// 2 pi sqrt(L / g), its anchor held together to 0.1 mm.
TEST(WidePoints, PendulumKeepsPeriodAndAnchor) {
  for (const int lanes : {4, 8}) for (const bool exact : {false, true}) {
    World w(wideDef(lanes, 1, exact));
    const double L = 1.0, theta = 0.05;
    const BodyId top = addStatic(w, Transform(Vec3(0, 0, 2), Quat::Identity()));
    const BodyId bob = addDynamic(w, 1.0, Mat3::Identity() * 1e-6,
                                  Transform(Vec3(L * std::sin(theta), 0, 2 - L * std::cos(theta)),
                                            Quat::Identity()));
    BallJointDef j;
    j.body_a = top;
    j.body_b = bob;
    j.frame_b.p = Vec3(-L * std::sin(theta), 0, L * std::cos(theta));
    const JointId id = w.createBallJoint(j);
    double worst = 0.0;
    double prev = w.comPosition(bob).x(), t_first = -1, t_last = -1;
    int crossings = 0;
    for (int i = 0; i < 6000; ++i) {
      w.step(kDt);
      worst = std::max(worst, w.jointAnchorError(id).norm());
      const double x = w.comPosition(bob).x();
      if (prev > 0 && x <= 0) {
        const double t = w.time() - kDt * x / (x - prev);
        if (t_first < 0) t_first = t;
        t_last = t;
        ++crossings;
      }
      prev = x;
    }
    ASSERT_GE(crossings, 3);
    const double T = (t_last - t_first) / (crossings - 1), expected = 2 * M_PI * std::sqrt(L / kG);
    EXPECT_NEAR(T, expected, 2e-3 * expected) << "lanes " << lanes << " exact " << exact;
    EXPECT_LT(worst, 1e-4) << "lanes " << lanes << " exact " << exact;
    std::printf("[ pendulum ] lanes %d exact %d: period %.5f s (closed form %.5f), anchor error "
                "%.2e m\n", lanes, int(exact), T, expected, worst);
  }
}

// Ten links hanging at rest: each joint carries the weight of the links below it.
TEST(WidePoints, HangingChainCarriesWeightBelow) {
  for (const int lanes : {4, 8}) for (const bool exact : {false, true}) {
    World w(wideDef(lanes, 1, exact));
    std::vector<double> masses;
    for (int i = 0; i < 10; ++i) masses.push_back(0.5 + 0.3 * i);
    std::vector<JointId> joints;
    addChain(w, Vec3(0, 0, 4), masses, -Vec3::UnitZ(), &joints);
    for (int i = 0; i < 300; ++i) w.step(kDt);
    double below = 0.0, worst = 0.0;
    for (int i = 9; i >= 0; --i) {
      below += masses[i];
      const double expected = below * kG, f = w.jointForce(joints[i]);
      EXPECT_NEAR(f, expected, 1e-3 * expected)
          << "lanes " << lanes << " exact " << exact << " joint " << i;
      worst = std::max(worst, std::abs(f - expected) / expected);
    }
    std::printf("[ chain    ] lanes %d exact %d: worst relative joint force error %.2e\n", lanes,
                int(exact), worst);
  }
}

// A spinning free pair on a ball joint (no gravity) keeps its linear momentum to double
// rounding: the lanes' impulse reaches both bodies through their double inverse masses.
TEST(WidePoints, FreePairKeepsLinearMomentum) {
  for (const int lanes : {4, 8}) {
    WorldDef def = wideDef(lanes, 1);
    def.gravity.setZero();
    World w(def);
    const BodyId a = addDynamic(w, 3.0, diag(0.03, 0.05, 0.04), Transform(Vec3(0, 0, 0), Quat::Identity()),
                                Vec3::Zero(), Vec3(0.5, -0.2, 0.1), Vec3(0.4, -1.0, 2.0));
    const BodyId b = addDynamic(w, 1.2, diag(0.01, 0.012, 0.008),
                                Transform(Vec3(0.4, 0.1, 0.0), Quat::Identity()), Vec3::Zero(),
                                Vec3(-1.0, 0.5, 0.3), Vec3(-2.0, 1.5, 0.5));
    const Transform f(Vec3(0.2, 0.05, 0.0), Quat::Identity());
    BallJointDef j;
    j.body_a = a, j.body_b = b, j.frame_a = local(w, a, f), j.frame_b = local(w, b, f);
    w.createBallJoint(j);
    const Vec3 p0 = w.linearMomentum();
    for (int i = 0; i < 2000; ++i) w.step(kDt);
    const double dp = (w.linearMomentum() - p0).norm() / p0.norm();
    EXPECT_LT(dp, 1e-12) << "lanes " << lanes;
    std::printf("[ momentum ] lanes %d: relative change of the linear momentum %.2e\n", lanes, dp);
  }
}

// A free pair spinning about a ball joint (no gravity), a light rod on a long lever turning
// half a radian per step: the lanes form K^-1 each substep from that substep's anchors, so they
// hold the anchor as the scalar rows (lanes 1, the reference) do and the rotation gains no
// energy; a K^-1 kept from the first substep overshoots as the rod turns away and blows up.
// Without the joint trees the soft rows alone stretch at this lever, scalar rows as much.
TEST(WidePoints, FastSpinningPairHoldsAnchorWithoutGainingEnergy) {
  for (const int lanes : {1, 4, 8}) for (const bool exact : {false, true}) {
    WorldDef def = wideDef(lanes, 1, exact);
    def.gravity.setZero();
    World w(def);
    const Vec3 omega(0.0, 2.0, 30.0);
    const BodyId a = addDynamic(w, 4.0, diag(0.05, 0.04, 0.03), Transform(Vec3::Zero(), Quat::Identity()),
                                Vec3::Zero(), Vec3::Zero(), omega);
    // a rod along x, 0.6 m long, its end on the hub 5 cm from the hub's centre
    const Vec3 rod_c(0.35, 0.0, 0.0);
    const BodyId b = addDynamic(w, 0.5, diag(1e-4, 0.015, 0.015), Transform(rod_c, Quat::Identity()),
                                Vec3::Zero(), omega.cross(rod_c), omega);
    const Transform f(Vec3(0.05, 0.0, 0.0), Quat::Identity());
    BallJointDef j;
    j.body_a = a, j.body_b = b, j.frame_a = local(w, a, f), j.frame_b = local(w, b, f);
    const JointId id = w.createBallJoint(j);
    const double e0 = w.kineticEnergy();
    double worst = 0.0, e_max = e0;
    for (int i = 0; i < 600; ++i) {
      w.step(1.0 / 60.0);
      worst = std::max(worst, w.jointAnchorError(id).norm());
      e_max = std::max(e_max, w.kineticEnergy());
    }
    EXPECT_LT(worst, exact ? 1e-3 : 0.1) << "lanes " << lanes << " exact " << exact;
    EXPECT_LT(e_max, 1.001 * e0) << "lanes " << lanes << " exact " << exact;
    std::printf("[ spin     ] lanes %d exact %d: anchor error %.2e m, energy max/start %.6f, "
                "end/start %.6f\n", lanes, int(exact), worst, e_max / e0, w.kineticEnergy() / e0);
  }
}

// A bob hanging from a fixed point comes to rest to far below float's resolution of its
// velocity change per substep (g h): each impulse increment reaches the body as computed, not
// rounded to the ulp of the accumulated impulse.
TEST(WidePoints, HangingBobComesToRest) {
  for (const int lanes : {4, 8}) {
    World w(wideDef(lanes, 1));
    std::vector<JointId> joints;
    const std::vector<BodyId> bob = addChain(w, Vec3(0, 0, 2), {2.0}, -Vec3::UnitZ(), &joints);
    for (int i = 0; i < 60; ++i) w.step(1.0 / 60.0);
    const double v = w.bodyState(bob[0]).linear_velocity.norm();
    EXPECT_LT(v, 1e-9) << "lanes " << lanes;
    EXPECT_NEAR(w.jointForce(joints[0]), 2.0 * kG, 1e-6 * 2.0 * kG) << "lanes " << lanes;
    std::printf("[ bob      ] lanes %d: speed %.2e m/s\n", lanes, v);
  }
}

// IslandCounters' wide solver fields. addRagdoll's torso joins five joints, so first fit gives
// its 9 joints 5 colours: the neck, both elbows and both knees in one, a shoulder or a hip alone
// in each other. Alone, a humanoid's records are one per colour (5 x 8 lanes for 9 rows); two
// humanoids of one range (one thread) share them: 10 rows in the first colour take two records
// and 2 in each other one, 6 x 8 lanes for 18 rows. A box resting on the ground is one manifold
// in a block of its own; the double rows count nothing.
TEST(WidePoints, CountersGiveTheRowsInTheLanesAndTheLanes) {
  const auto counters = [](int lanes, int ragdolls, bool box) {
    World w(wideDef(lanes, 1));
    for (int k = 0; k < ragdolls; ++k)
      addRagdoll(w, Vec3(3.0 * k, 0, 5.0), Vec3::Zero(), Vec3::Zero());
    if (box) {
      addGround(w);
      addBox(w, Vec3(0.2, 0.2, 0.2), 1.0, Vec3(-3.0, 0, 0.2));
    }
    w.step(kDt);
    return w.islandCounters();
  };
  IslandCounters c = counters(8, 1, false);
  EXPECT_EQ(c.lane_batches, 1);
  EXPECT_EQ(c.joint_lane_rows, 9);
  EXPECT_EQ(c.joint_lanes, 40);
  EXPECT_EQ(c.contact_lane_rows, 0);
  EXPECT_EQ(c.contact_lanes, 0);
  c = counters(4, 2, false);
  EXPECT_EQ(c.lane_batches, 1) << "two islands in one range";
  EXPECT_EQ(c.joint_lane_rows, 18);
  EXPECT_EQ(c.joint_lanes, 48);
  c = counters(8, 0, true);
  EXPECT_EQ(c.lane_batches, 1);
  EXPECT_EQ(c.contact_lane_rows, 1);
  EXPECT_EQ(c.contact_lanes, 8);
  EXPECT_EQ(c.joint_lanes, 0);
  c = counters(1, 2, true);
  EXPECT_EQ(c.lane_batches + c.joint_lane_rows + c.joint_lanes + c.contact_lane_rows +
                c.contact_lanes,
            0);
}
