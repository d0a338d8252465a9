// A hinge's axis part solved in its anchor's float lane (point_row_wide.inc): the kernel against
// the double parts (part_hinge_axis.hpp, part_point.hpp) for the same state, 4 and 8 lanes give
// the same bits, and in a world the lanes hold a hinge's axis as the scalar rows do.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <random>
#include <vector>

#include "body.hpp"
#include "joint_test_util.hpp"
#include "lane_bodies.hpp"
#include "lane_width.hpp"
#include "part_hinge_axis.hpp"
#include "part_point.hpp"
#include "point_row_test_util.hpp"
#include "point_row_wide.hpp"
#include "ragdoll_sim/state_hash.hpp"
#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"
#include "softness.hpp"
#include "world_tuning.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {

// One block: lanes [0, kHinges) hold hinges, the rest balls; lane l joins bodies 2l and 2l + 1.
constexpr int kHinges = 6;

struct KernelCase {
  std::vector<SolverBody> bodies;
  std::vector<HingeAxisPart> axes;
  std::vector<PointPart> points;
  std::vector<Vec3> errors;
};

Mat3 randomRotation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return Quat(Eigen::AngleAxisd(3.0 * u(rng), Vec3(u(rng), u(rng), u(rng) + 2.0).normalized()))
      .toRotationMatrix();
}

KernelCase makeCase(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  KernelCase k;
  k.bodies.resize(2 * kRowBlock);
  for (SolverBody& b : k.bodies) {
    b.v = Vec3(u(rng), u(rng), u(rng));
    b.w = Vec3(u(rng), u(rng), u(rng));
    b.inv_mass = 0.2 + 2.0 * pos(rng);
    const Mat3 R = randomRotation(rng);
    b.inv_inertia = R * Vec3(1 + 19 * pos(rng), 1 + 19 * pos(rng), 1 + 19 * pos(rng)).asDiagonal() *
                    R.transpose();
  }
  k.axes.resize(kRowBlock);
  k.points.resize(kRowBlock);
  for (int l = 0; l < kRowBlock; ++l) {
    PointPart& p = k.points[l];
    p.rA = 0.3 * Vec3(u(rng), u(rng), u(rng));
    p.rB = 0.3 * Vec3(u(rng), u(rng), u(rng));
    p.impulse = 0.5 * Vec3(u(rng), u(rng), u(rng));
    const Vec3 error = 0.01 * Vec3(u(rng), u(rng), u(rng));
    p.delta_center = error - (p.rB - p.rA);  // error(A, B) with the deltas 0
    k.errors.push_back(error);
    if (l >= kHinges) continue;
    HingeAxisPart& h = k.axes[l];
    const Mat3 R = randomRotation(rng);
    const Vec3 a1 = (R * Vec3(0.02 * u(rng), 0.02 * u(rng), 1.0)).normalized();
    const Vec3 b2 = R * Vec3::UnitX(), c2 = R * Vec3::UnitY();
    h.u1 = b2.cross(a1);
    h.u2 = c2.cross(a1);
    h.C = Eigen::Vector2d(a1.dot(b2), a1.dot(c2));
    h.impulse = 0.3 * Eigen::Vector2d(u(rng), u(rng));
  }
  return k;
}

void putSym(float (&f)[6][kRowBlock], int i, const Mat3& m) {
  const double e[6] = {m(0, 0), m(1, 1), m(2, 2), m(0, 1), m(0, 2), m(1, 2)};
  for (int c = 0; c < 6; ++c) f[c][i] = float(e[c]);
}
void putVec(float (&f)[3][kRowBlock], int i, const Vec3& v) {
  for (int c = 0; c < 3; ++c) f[c][i] = float(v[c]);
}

PointRowBlock makeBlock(const KernelCase& k) {
  PointRowBlock b{};
  for (int l = 0; l < kRowBlock; ++l) {
    const SolverBody &A = k.bodies[2 * l], &B = k.bodies[2 * l + 1];
    b.body_a[l] = 2 * l, b.body_b[l] = 2 * l + 1;
    putVec(b.r_a, l, k.points[l].rA);
    putVec(b.r_b, l, k.points[l].rB);
    putSym(b.ii_a, l, A.inv_inertia);
    putSym(b.ii_b, l, B.inv_inertia);
    b.inv_mass[l] = float(A.inv_mass + B.inv_mass);
    putVec(b.error, l, k.errors[l]);
    putVec(b.impulse, l, k.points[l].impulse);
    if (l >= kHinges) continue;
    const HingeAxisPart& h = k.axes[l];
    putVec(b.axis_u1, l, h.u1);
    putVec(b.axis_u2, l, h.u2);
    for (int c = 0; c < 2; ++c) {
      b.axis_error[c][l] = float(h.C[c]);
      b.axis_impulse[c][l] = float(h.impulse[c]);
    }
    b.axis_rows = 1;
  }
  return b;
}

// The same in double, each joint's axis before its anchor (HingeJoint's order).
void runDouble(KernelCase& k) {
  for (int l = 0; l < kRowBlock; ++l) {
    SolverBody &A = k.bodies[2 * l], &B = k.bodies[2 * l + 1];
    if (l < kHinges) {
      k.axes[l].updateMass(A, B, true);
      k.axes[l].warmStart(A, B);
    }
    k.points[l].updateMass(A, B, 0.0, true);
    k.points[l].warmStart(A, B);
    for (const bool use_bias : {true, false}) {
      if (l < kHinges) k.axes[l].solve(A, B, kLaneSoft, use_bias);
      k.points[l].solve(A, B, kLaneSoft, use_bias);
    }
  }
}

WorldDef laneDef(int lanes, int threads) {
  WorldDef d;
  d.solver.exact_joints = false;  // the lanes alone hold the joints
  d.solver.position_iterations = d.solver.anchor_iterations = 0;
  d.sleep.enabled = false;
  d.solver.lanes = lanes;
  d.threads = threads;
  return d;
}

// A chain of boxes on hinges about alternating axes, hanging from a static point and spun.
std::vector<JointId> addHingeChain(World& w, const Vec3& top, int links) {
  const BodyId root = addStatic(w, Transform(top, Quat::Identity()));
  BodyId prev = root;
  std::vector<JointId> joints;
  for (int i = 0; i < links; ++i) {
    const Vec3 joint = top - Vec3(0.05 * i, 0, 0.3 * i);
    const Vec3 half(0.04, 0.03, 0.15);
    const double m = 1.0 + 0.2 * i;
    const BodyId b = addDynamic(w, m, boxInertia(half, m),
                                Transform(joint - Vec3(0, 0, 0.15), Quat::Identity()), Vec3::Zero(),
                                Vec3(0.3, 0.1 * i, 0), Vec3(0.5, -1.0, 2.0 - 0.3 * i));
    const Transform f(joint, Quat::Identity());
    HingeJointDef j;
    j.body_a = prev, j.body_b = b, j.frame_a = local(w, prev, f), j.frame_b = local(w, b, f);
    j.axis = i % 2 ? Vec3::UnitX() : Vec3::UnitY();
    joints.push_back(w.createHingeJoint(j));
    prev = b;
  }
  return joints;
}

uint64_t chainHash(int lanes, int threads, int steps) {
  World w(laneDef(lanes, threads));
  addHingeChain(w, Vec3(0, 0, 4), 12);
  addHingeChain(w, Vec3(2, 0, 4), 5);
  for (int i = 0; i < steps; ++i) w.step(1.0 / 240.0);
  return hashStates(w);
}

}  // namespace

// The lanes' impulses and velocities after a warm start and two sweeps are the double parts'
// to float rounding; the ball lanes' axis rows stay exactly 0; 4 and 8 lanes give the same bits.
TEST(JointLanes, HingeAxisKernelMatchesDoubleParts) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    KernelCase d = makeCase(seed);
    const std::vector<SolverBody> start = d.bodies;
    PointRowBlock b4 = makeBlock(d);
    std::vector<SolverBody> f4 = start;
    runLanes(4, b4, f4);
    runDouble(d);
    double worst = 0.0, moved = 0.0;
    for (int l = 0; l < kRowBlock; ++l) {
      if (l >= kHinges) {
        EXPECT_EQ(b4.axis_impulse[0][l], 0.0f);
        EXPECT_EQ(b4.axis_impulse[1][l], 0.0f);
        EXPECT_EQ(b4.axis_k_inv[0][l], 0.0f);
        continue;
      }
      const HingeAxisPart& h = d.axes[l];
      for (int c = 0; c < 2; ++c) {
        worst = std::max(worst, std::abs(b4.axis_impulse[c][l] - h.impulse[c]) /
                                    (1.0 + std::abs(h.impulse[c])));
        moved = std::max(moved, std::abs(h.impulse[c] - makeCase(seed).axes[l].impulse[c]));
      }
    }
    for (size_t i = 0; i < start.size(); ++i) {
      worst = std::max(worst, (f4[i].w - d.bodies[i].w).norm() / (1.0 + d.bodies[i].w.norm()));
      worst = std::max(worst, (f4[i].v - d.bodies[i].v).norm() / (1.0 + d.bodies[i].v.norm()));
    }
    EXPECT_LT(worst, 2e-5) << "seed " << seed;
    EXPECT_GT(moved, 0.05) << "the sweeps changed the axis impulses (seed " << seed << ")";
    std::printf("[ kernel   ] seed %u: worst relative difference to double %.2e\n", seed, worst);
    if (cpuHasAvx2()) expectEightLanesSameBits(makeBlock(makeCase(seed)), start, b4, f4);
  }
}

// Hinge chains: 4 and 8 lanes, one thread and two, the same bits; not the scalar path.
TEST(JointLanes, HingeChainSameBitsAtFourAndEightLanesAndAnyThreads) {
  const int steps = 300;
  const uint64_t h4 = chainHash(4, 1, steps);
  EXPECT_EQ(h4, chainHash(8, 1, steps));
  EXPECT_EQ(h4, chainHash(4, 2, steps));
  EXPECT_EQ(h4, chainHash(8, 2, steps));
  EXPECT_NE(h4, chainHash(1, 1, steps));
  std::printf("[ chain    ] hash %016llx (avx2 %d)\n", (unsigned long long)h4, int(cpuHasAvx2()));
}

// The threads' ranges of islands keep a reserve to steal always, never, or after an uneven step
// (WorldTuning::range_reserve): eight chains (eight islands, 56 bodies: solved in parallel) on
// two threads give the bits of one thread whichever.
TEST(JointLanes, RangeReserveChangesNoBit) {
  const auto run = [](int threads, int reserve) {
    World w(laneDef(8, threads));
    WorldTuning tuning = WorldInternals::tuning(w);
    tuning.range_reserve = reserve;
    WorldInternals::setTuning(w, tuning);
    for (int c = 0; c < 8; ++c) addHingeChain(w, Vec3(2.0 * c, 0, 4), 7);
    for (int i = 0; i < 200; ++i) w.step(1.0 / 240.0);
    return hashStates(w);
  };
  const uint64_t one = run(1, -1);
  for (const int reserve : {-1, 0, 1}) EXPECT_EQ(one, run(2, reserve)) << "reserve " << reserve;
}

// A beam along its hinge's axis, spinning about it on a static post: the axis rows alone hold
// its weight's torque m g L about the horizontal, and in the lanes they keep the axis as
// straight as the scalar rows do; the torque reported comes from the lanes' impulses.
TEST(JointLanes, AxisRowsHoldACantileverAsTheScalarRowsDo) {
  double scalar_worst = -1.0;
  for (const int lanes : {1, 4, 8}) {
    World w(laneDef(lanes, 1));
    const double m = 2.0, L = 0.5;
    const Vec3 half(L, 0.03, 0.03);
    const BodyId post = addStatic(w, Transform(Vec3(0, 0, 1), Quat::Identity()));
    const BodyId beam = addDynamic(w, m, boxInertia(half, m),
                                   Transform(Vec3(L, 0, 1), Quat::Identity()), Vec3::Zero(),
                                   Vec3::Zero(), Vec3(3.0, 0, 0));
    const Transform f(Vec3(0, 0, 1), Quat::Identity());
    HingeJointDef j;
    j.body_a = post, j.body_b = beam, j.frame_a = local(w, post, f), j.frame_b = local(w, beam, f);
    j.axis = Vec3::UnitX();
    const JointId id = w.createHingeJoint(j);
    double worst = 0.0;
    for (int i = 0; i < 480; ++i) {
      w.step(1.0 / 240.0);
      const Vec3 x = w.bodyPose(beam).q * Vec3::UnitX();
      worst = std::max(worst, std::acos(std::min(1.0, x.x())));
    }
    const Vec3 torque = w.jointWrench(id).torque;
    const double expected = m * kG * L;
    EXPECT_NEAR(std::hypot(torque.y(), torque.z()), expected, 2e-3 * expected) << "lanes " << lanes;
    EXPECT_LT(worst, 1e-3) << "lanes " << lanes;
    if (lanes == 1) scalar_worst = worst;
    else EXPECT_LT(worst, 1.5 * scalar_worst + 1e-6) << "lanes " << lanes;
    std::printf("[ beam     ] lanes %d: axis error %.2e rad, torque %.4f N m (m g L %.4f)\n", lanes,
                worst, std::hypot(torque.y(), torque.z()), expected);
  }
}

// A ball with swing-twist limits recomputes its Euler angles exactly after each position update
// (BallJoint::advance); in the lanes its Euler rows (here from the damping) must keep those, not
// the lanes' first-order advance. Without projections the solver's angles after the step are
// those of the final poses.
TEST(JointLanes, SwingTwistBallKeepsItsExactAngles) {
  for (const int lanes : {1, 4, 8}) {
    WorldDef def = zeroG();
    def.sleep.enabled = false;
    def.solver.lanes = lanes;
    def.solver.position_iterations = 0;
    def.solver.anchor_iterations = 0;
    def.solver.exact_joints = false;
    World w(def);
    BallJointDef bj;
    std::tie(bj.body_a, bj.body_b) = addAnchoredArm(w, Vec3(3.0, 8.0, -6.0));
    bj.axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
    bj.enable_limits = true;
    bj.limit_mode = BallLimitMode::SwingTwist;
    bj.swing_cone_angle = 1.2;
    bj.twist_lower = -1.0;
    bj.twist_upper = 1.0;
    for (JointMotor& m : bj.motors) m.damping = 0.01;
    const JointId joint = w.createBallJoint(bj);
    double worst = 0.0;
    for (int i = 0; i < 20; ++i) {
      w.step(kDt);
      const std::vector<double> solver = WorldInternals::solverAngles(w, joint);
      const std::array<double, 3> exact = w.ballAngles(joint);
      ASSERT_EQ(solver.size(), 3u) << "lanes " << lanes << ", step " << i;
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(solver[k] - exact[k]));
    }
    EXPECT_LT(worst, 1e-10) << "lanes " << lanes;
  }
}

namespace {

// Chains of Euler-limited balls and limited hinges, some driven or damped, swinging into their
// limits for 400 steps with the tuning set by `tune`: the state's hash, and the worst excess of
// a hinge past its limits into *worst_limit. midway(world, the hinges) runs after step 200.
template <class Tune>
uint64_t limitedChains(int lanes, Tune&& tune, double* worst_limit,
                       const std::function<void(World&, const std::vector<JointId>&)>& midway = {}) {
  WorldDef def;
  def.sleep.enabled = false;
  def.solver.lanes = lanes;
  World w(def);
  WorldTuning tuning = WorldInternals::tuning(w);
  tune(tuning);
  WorldInternals::setTuning(w, tuning);
  addGround(w);
  const Vec3 half(0.1, 0.05, 0.05);
  std::vector<JointId> hinges;
  for (int c = 0; c < 3; ++c) {
    BodyId prev = addBox(w, half, 1.0, Vec3(0, 0.5 * c, 1.0));
    for (int k = 1; k < 10; ++k) {
      const BodyId b = addBox(w, half, 1.0 + 0.1 * k, Vec3(0.2 * k, 0.5 * c, 1.0 + 0.01 * k));
      if ((k + c) % 2) {
        BallJointDef j;
        j.body_a = prev, j.body_b = b;
        j.frame_a.p = Vec3(0.1, 0, 0), j.frame_b.p = Vec3(-0.1, 0, 0);
        j.enable_limits = true;
        j.lower = {-0.3, -0.2, -0.4}, j.upper = {0.3, 0.25, 0.1};
        if (k % 3 == 0) j.motors[2].damping = 0.1;
        if (k % 4 == 0) j.motors[0] = {true, 0.2, 0.0, 3.0, 1.0, 4.0, 0.0};
        w.createBallJoint(j);
      } else {
        HingeJointDef j;
        j.body_a = prev, j.body_b = b;
        j.frame_a.p = Vec3(0.1, 0, 0), j.frame_b.p = Vec3(-0.1, 0, 0);
        j.axis = Vec3::UnitY();
        j.enable_limit = true, j.lower = -0.5, j.upper = 0.35;
        if (k % 3 == 1) j.motor = {true, 0.0, 1.0, 0.0, 1.0, 2.0, 0.0};
        hinges.push_back(w.createHingeJoint(j));
      }
      prev = b;
    }
  }
  for (int i = 0; i < 400; ++i) {
    if (i == 200 && midway) midway(w, hinges);
    w.step(1e-3);
    for (const JointId h : hinges) {
      const double a = w.hingeAngle(h);
      *worst_limit = std::max(*worst_limit, std::max(-0.5 - a, a - 0.35));
    }
  }
  return hashStates(w);
}

// The chains' state with a switch of WorldTuning on and with it off, at each width of `widths`
// (both lane widths unless given): the same bits, with a hinge near its limit (so that the limit
// rows take part).
void expectSwitchChangesNoBit(
    bool WorldTuning::*field,
    const std::function<void(World&, const std::vector<JointId>&)>& midway = {},
    std::initializer_list<int> widths = {4, 8}) {
  for (const int lanes : widths) {
    double reach = -1.0;
    const auto set = [field](bool on) { return [field, on](WorldTuning& t) { t.*field = on; }; };
    const uint64_t on = limitedChains(lanes, set(true), &reach, midway);
    const uint64_t off = limitedChains(lanes, set(false), &reach, midway);
    EXPECT_EQ(on, off) << "lanes " << lanes;
    EXPECT_GT(reach, -0.01) << "lanes " << lanes << ": no hinge came within 0.01 rad of a limit";
  }
}

}  // namespace

// After the first substep the wide pass keeps the angles it advanced and takes only those the
// joints recomputed (a limit within reach, a motor): the chains' state must be the one of
// putting every angle in at every substep.
TEST(JointLanes, KeptLaneAnglesChangeNoBit) {
  expectSwitchChangesNoBit(&WorldTuning::lane_angles_kept);
}

// The joints' exact angles computed in the lanes, several at a time, at every substep where a
// joint's warm start would recompute its own (PointLanes::exactAngles), and with double rows
// (lanes 1) those of the first substep (firstSubstepAngles), give the chains' state of each
// joint computing its own.
TEST(JointLanes, ExactAnglesInLanesChangeNoBit) {
  expectSwitchChangesNoBit(&WorldTuning::lane_exact_angles, {}, {1, 4, 8});
}

// The lanes keep their exact-angle jobs, which point into the bodies' arrays, from step to step
// while the lanes stay: bodies created midway move those arrays (a job that kept the old ones
// would read freed memory and the angles of the step they were made in), and a motor turned on
// gives a block motor rows. The chains' state must still be the one of each joint computing its
// own angles.
TEST(JointLanes, ExactAngleJobsFollowMovedBodyArrays) {
  expectSwitchChangesNoBit(&WorldTuning::lane_exact_angles,
                           [](World& w, const std::vector<JointId>& hinges) {
                             for (int k = 0; k < 600; ++k) {
                               BodyDef d;
                               d.type = BodyType::Static;
                               d.pose = Transform(Vec3(100.0 + k, 50.0, 0.0), Quat::Identity());
                               w.addShape(w.createBody(d), {Geometry::sphere(0.1), Transform(),
                                                            Material()});
                             }
                             w.setJointMotor(hinges[0], 0, {true, 0.0, 1.0, 0.0, 1.0, 2.0, 0.0});
                           });
}
