// The fault guard of World::step: a body whose state goes non-finite (a NaN force set through
// the core API, an infinite impulse, an overflow inside the solver) is reset to its last finite
// pose with zero velocity and reported; bodies of other islands go on exactly as without it;
// velocities stay within WorldDef's caps (a huge impulse is clamped before the solver), also
// for a 1e6:1 mass ratio. A body whose centre of mass leaves the world range (kWorldRange) is a
// fault too: it never reports a coordinate beyond it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {

constexpr double kDt = 1e-3;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

bool finite(const BodyState& s) {
  return s.pose.p.allFinite() && s.pose.q.coeffs().allFinite() && s.linear_velocity.allFinite() &&
         s.angular_velocity.allFinite();
}

// Exactly the same state (the guard must not touch bodies of other islands).
void expectSame(const BodyState& a, const BodyState& b, const char* what) {
  EXPECT_EQ(a.pose.p, b.pose.p) << what;
  EXPECT_EQ(a.pose.q.coeffs(), b.pose.q.coeffs()) << what;
  EXPECT_EQ(a.linear_velocity, b.linear_velocity) << what;
  EXPECT_EQ(a.angular_velocity, b.angular_velocity) << what;
}

// Two chains in separate islands: `hit` gets the fault, `other` must not notice.
struct TwoChains {
  World w;
  std::vector<BodyId> hit, other;
  explicit TwoChains(double tip_mass = 1.0) {
    hit = addChain(w, Vec3(0, 0, 2), {1.0, 1.0, tip_mass});
    other = addChain(w, Vec3(0, 3, 2), {1.0, 1.0, 1.0});
  }
  void step(int n) {
    for (int i = 0; i < n; ++i) w.step(kDt);
  }
};

}  // namespace

TEST(BodyFaults, NaNForceResetsThatBodyOthersGoOn) {
  TwoChains faulty, reference;
  faulty.step(200);
  reference.step(200);
  const BodyId target = faulty.hit[1];
  const BodyState before = faulty.w.bodyState(target);
  ASSERT_GT(before.linear_velocity.norm(), 0.1) << "the chain should be swinging";

  // Bypasses every check of the node: straight into the core.
  faulty.w.applyForce(target, Vec3(kNaN, 0, 0), faulty.w.comPosition(target));
  faulty.step(1);
  reference.step(1);

  const std::vector<BodyFault> faults = faulty.w.takeBodyFaults();
  ASSERT_EQ(faults.size(), 1u);
  EXPECT_EQ(faults[0].body, target);
  EXPECT_EQ(faults[0].cause, BodyFaultCause::Input);
  EXPECT_NEAR(faults[0].time, 0.2, 1e-9);
  EXPECT_EQ(faulty.w.bodyFaultCount(), 1);
  EXPECT_TRUE(faulty.w.takeBodyFaults().empty()) << "taken once";

  // Reset to its last finite pose with zero velocity, then one step of gravity and joints.
  const BodyState after = faulty.w.bodyState(target);
  EXPECT_TRUE(finite(after));
  EXPECT_LT((after.pose.p - before.pose.p).norm(), 0.01);
  for (BodyId b : faulty.hit) EXPECT_TRUE(finite(faulty.w.bodyState(b)));
  for (size_t i = 0; i < faulty.other.size(); ++i)
    expectSame(faulty.w.bodyState(faulty.other[i]), reference.w.bodyState(reference.other[i]),
               "other island");

  faulty.step(500);
  reference.step(500);
  EXPECT_EQ(faulty.w.bodyFaultCount(), 1) << "one fault, then a healthy world";
  for (BodyId b : faulty.hit) EXPECT_TRUE(finite(faulty.w.bodyState(b)));
  for (size_t i = 0; i < faulty.other.size(); ++i)
    expectSame(faulty.w.bodyState(faulty.other[i]), reference.w.bodyState(reference.other[i]),
               "other island, 500 steps later");
}

// A free body shows the reset alone: zero velocity, then one step of gravity.
TEST(BodyFaults, NaNTorqueOnFreeBodyZeroesItsVelocity) {
  World w;
  const BodyId b = addDynamic(w, 2.0, Mat3::Identity() * 0.1, Transform(Vec3(0, 0, 5), Quat::Identity()),
                              Vec3::Zero(), Vec3(3, 0, 0), Vec3(0, 1, 0));
  for (int i = 0; i < 10; ++i) w.step(kDt);
  const Vec3 x0 = w.comPosition(b);
  w.applyTorque(b, Vec3(0, 0, kInf));
  w.step(kDt);
  ASSERT_EQ(w.takeBodyFaults().size(), 1u);
  const BodyState s = w.bodyState(b);
  EXPECT_NEAR((s.linear_velocity - Vec3(0, 0, -9.81 * kDt)).norm(), 0.0, 1e-12);
  EXPECT_EQ(s.angular_velocity, Vec3::Zero());
  EXPECT_LT((s.com_position - x0).norm(), 1e-4) << "back at the last finite pose, then 1 ms of fall";
}

TEST(BodyFaults, InfiniteImpulseIsResetNaNPoseToo) {
  TwoChains t;
  t.step(50);
  const BodyState before = t.w.bodyState(t.hit[2]);
  t.w.applyLinearImpulse(t.hit[2], Vec3(0, kInf, 0), t.w.comPosition(t.hit[2]));
  t.w.setBodyState(t.hit[0], Transform(Vec3(kNaN, 0, 0), Quat::Identity()), Vec3::Zero(),
                   Vec3::Zero());
  t.step(1);
  const std::vector<BodyFault> faults = t.w.takeBodyFaults();
  ASSERT_EQ(faults.size(), 2u);
  EXPECT_EQ(faults[0].body, t.hit[0]);  // in body order
  EXPECT_EQ(faults[1].body, t.hit[2]);
  for (const BodyFault& f : faults) EXPECT_EQ(f.cause, BodyFaultCause::Input);
  EXPECT_LT((t.w.bodyState(t.hit[2]).pose.p - before.pose.p).norm(), 0.01);
  t.step(300);
  EXPECT_EQ(t.w.bodyFaultCount(), 2);
  for (BodyId b : t.hit) EXPECT_TRUE(finite(t.w.bodyState(b)));
}

// A finite force that overflows inside the solver (1e308 N on 1 g: the acceleration is inf)
// passes the input check; the step leaves the whole island NaN, and every body of it is reset
// to its pose at the start of that step. The joints' warm-start impulses (NaN) are cleared, so
// the next steps are healthy; the other island never notices.
TEST(BodyFaults, SolverOverflowResetsTheIslandOnly) {
  TwoChains faulty(1e-3), reference(1e-3);
  faulty.step(100);
  reference.step(100);
  std::vector<BodyState> start;
  for (BodyId b : faulty.hit) start.push_back(faulty.w.bodyState(b));
  const BodyId light = faulty.hit[2];
  faulty.w.applyForce(light, Vec3(0, 0, 1e308), faulty.w.comPosition(light));
  faulty.step(1);
  reference.step(1);

  const std::vector<BodyFault> faults = faulty.w.takeBodyFaults();
  ASSERT_FALSE(faults.empty());
  bool light_reset = false;
  for (const BodyFault& f : faults) {
    EXPECT_EQ(f.cause, BodyFaultCause::Solver);
    EXPECT_NE(std::find(faulty.hit.begin(), faulty.hit.end(), f.body), faulty.hit.end())
        << "body " << f.body.index << " is not in the faulty island";
    light_reset |= f.body == light;
  }
  EXPECT_TRUE(light_reset);
  for (const BodyFault& f : faults) {
    const size_t k = size_t(std::find(faulty.hit.begin(), faulty.hit.end(), f.body) - faulty.hit.begin());
    const BodyState s = faulty.w.bodyState(f.body);
    EXPECT_EQ(s.pose.p, start[k].pose.p) << "reset to the pose at the start of the step";
    EXPECT_EQ(s.linear_velocity, Vec3::Zero());
    EXPECT_EQ(s.angular_velocity, Vec3::Zero());
  }
  for (size_t i = 0; i < faulty.other.size(); ++i)
    expectSame(faulty.w.bodyState(faulty.other[i]), reference.w.bodyState(reference.other[i]),
               "other island");

  const int64_t count = faulty.w.bodyFaultCount();
  faulty.step(500);
  reference.step(500);
  EXPECT_EQ(faulty.w.bodyFaultCount(), count) << "the warm start carried the NaN on";
  for (BodyId b : faulty.hit) EXPECT_TRUE(finite(faulty.w.bodyState(b)));
  for (size_t i = 0; i < faulty.other.size(); ++i)
    expectSame(faulty.w.bodyState(faulty.other[i]), reference.w.bodyState(reference.other[i]),
               "other island, 500 steps later");
}

// A body the solver leaves non-finite counts at rest for sleep, as its reset leaves it: with a
// sleep time of one step, the island it brought down goes to sleep in that very step.
TEST(BodyFaults, SolverFaultedIslandSleepsAsReset) {
  WorldDef def;
  def.gravity.setZero();
  def.sleep.time = kDt;
  World w(def);
  const std::vector<BodyId> chain = addChain(w, Vec3(0, 0, 2), {1.0, 1.0, 1e-3});
  w.applyForce(chain[2], Vec3(0, 0, 1e308), w.comPosition(chain[2]));
  w.step(kDt);
  ASSERT_FALSE(w.takeBodyFaults().empty());
  for (BodyId b : chain) EXPECT_FALSE(w.isAwake(b)) << "body " << b.index;
}

// A huge (finite) impulse is clamped to max_linear_speed before the solver integrates it: the
// body moves at most max_linear_speed * dt in the step, and no state goes non-finite.
TEST(BodyFaults, HugeImpulseClampedToConfiguredCaps) {
  for (double cap : {100.0, 5.0}) {
    WorldDef def;
    def.solver.max_linear_speed = cap;
    def.solver.max_angular_speed = 2.0 * cap;
    World w(def);
    const std::vector<BodyId> chain = addChain(w, Vec3(0, 0, 2), {1.0, 1.0, 1.0});
    for (int i = 0; i < 10; ++i) w.step(kDt);
    const BodyId tip = chain.back();
    const Vec3 p0 = w.comPosition(tip);
    w.applyLinearImpulse(tip, Vec3(1e12, 0, 1e12), p0 + Vec3(0, 0.05, 0));
    w.step(kDt);
    EXPECT_LT((w.comPosition(tip) - p0).norm(), cap * kDt * 1.01) << "cap " << cap;
    for (int i = 0; i < 1000; ++i) {
      w.step(kDt);
      for (BodyId b : chain) {
        const BodyState s = w.bodyState(b);
        ASSERT_TRUE(finite(s)) << "cap " << cap << ", step " << i;
        ASSERT_LE(s.linear_velocity.norm(), cap * (1 + 1e-12));
        ASSERT_LE(s.angular_velocity.norm(), 2.0 * cap * (1 + 1e-12));
      }
    }
    EXPECT_EQ(w.bodyFaultCount(), 0) << "a finite impulse is clamped, not a fault";
  }
}

// A cap lowered between steps holds from the next step on, also for a body no command touched
// since the last step (which the guard otherwise skips): it moves the new cap times dt.
TEST(BodyFaults, LoweredCapClampsBodiesTheLastStepLeftAlone) {
  WorldDef def;
  def.gravity.setZero();
  World w(def);
  BodyDef bd;
  bd.linear_velocity = Vec3(5.0, 0.0, 0.0);
  const BodyId b = w.createBody(bd);
  w.step(kDt);
  const Vec3 p0 = w.comPosition(b);
  SolverSettings solver = w.def().solver;
  solver.max_linear_speed = 1.0;
  w.setSolverSettings(solver);
  w.step(kDt);
  EXPECT_NEAR((w.comPosition(b) - p0).norm(), 1.0 * kDt, 1e-9);  // the grid: 2^-33 m
  EXPECT_EQ(w.bodyState(b).linear_velocity, Vec3(1.0, 0.0, 0.0));
}

// 1e6:1 mass ratios: a 1 t body hanging from a 1 g one (joint chain, swinging), and a 1 t box
// dropped on a 1 g box lying on the ground. States stay finite and within the caps; any body
// that did go non-finite is reported and reset.
TEST(BodyFaults, MillionToOneMassRatioStaysFinite) {
  World w;
  addGround(w);
  const std::vector<BodyId> chain = addChain(w, Vec3(0, 0, 3), {1e-3, 1e3, 1e-3, 1e3});
  const Vec3 half(0.1, 0.1, 0.1);
  const BodyId light = addBox(w, half, 1e-3, Vec3(2, 0, 0.1));
  const BodyId heavy = addBox(w, half, 1e3, Vec3(2, 0, 0.8));
  std::vector<BodyId> all = chain;
  all.push_back(light);
  all.push_back(heavy);
  double max_v = 0.0;
  for (int i = 0; i < 3000; ++i) {
    w.step(kDt);
    for (BodyId b : all) {
      const BodyState s = w.bodyState(b);
      ASSERT_TRUE(finite(s)) << "step " << i;
      ASSERT_LE(s.linear_velocity.norm(), w.def().solver.max_linear_speed * (1 + 1e-12));
      ASSERT_LE(s.angular_velocity.norm(), w.def().solver.max_angular_speed * (1 + 1e-12));
      max_v = std::max(max_v, s.linear_velocity.norm());
    }
  }
  for (const BodyFault& f : w.takeBodyFaults())
    EXPECT_NE(std::find(all.begin(), all.end(), f.body), all.end());
  EXPECT_GT(w.comPosition(heavy).z(), 0.0) << "the heavy box fell through the ground";
  std::printf("[ ratio    ] 1e6:1: max speed %.3f m/s, faults %lld, heavy box z %.4f m\n", max_v,
              static_cast<long long>(w.bodyFaultCount()), w.comPosition(heavy).z());
  // Not asserted (solver quality, not the guard): how far the light links let the chain
  // stretch, and where the light box went.
  std::printf("[ ratio    ] chain: first link %.2f m from its anchor (0.30 built); light box "
              "moved %.3f m\n", (w.comPosition(chain[0]) - Vec3(0, 0, 3)).norm(),
              (w.comPosition(light) - Vec3(2, 0, 0.1)).norm());
}

TEST(BodyFaults, NonFiniteBodyDefIsRefused) {
  World w;
  BodyDef d;
  d.pose.p = Vec3(0, kNaN, 0);
  EXPECT_THROW(w.createBody(d), std::invalid_argument);
  d.pose.p.setZero();
  d.linear_velocity = Vec3(kInf, 0, 0);
  EXPECT_THROW(w.createBody(d), std::invalid_argument);
  d.linear_velocity.setZero();
  d.pose.p = Vec3(1.7e308, 0, 0);  // finite, but its centre of mass is not
  d.com = Vec3(1.7e308, 0, 0);
  EXPECT_THROW(w.createBody(d), std::invalid_argument);
  EXPECT_EQ(w.bodyCount(), 0);
}

// The largest |coordinate| of any body's centre of mass.
double farthest(const World& w) {
  double d = 0.0;
  for (int i = 0; i < w.bodyCount(); ++i)
    if (w.isValid(BodyId{i})) d = std::max(d, w.comPosition(BodyId{i}).cwiseAbs().maxCoeff());
  return d;
}

// Bodies flung outwards at the speed cap from just inside the world range (a free body, and a
// chain whose joints carry warm starts): the step that would take them out resets them to
// their pose at its start with zero velocity, reported as OutOfRange; no body ever reports a
// coordinate beyond kWorldRange, and the chain's joints hold afterwards.
TEST(BodyFaults, BodyFlungOutOfTheWorldRangeIsReset) {
  WorldDef def;
  def.gravity.setZero();
  World w(def);
  const double edge = kWorldRange - 0.5;
  const double cap = def.solver.max_linear_speed;
  const BodyId free = addDynamic(w, 1.0, Mat3::Identity() * 0.1,
                                 Transform(Vec3(edge, 0, 0), Quat::Identity()), Vec3::Zero(),
                                 Vec3(2 * cap, 0, 0), Vec3(0, 0, 3));
  std::vector<BodyId> chain;
  std::vector<JointId> joints;
  for (int k = 0; k < 3; ++k) {
    const Vec3 at(-(kWorldRange - 2.0) + 0.3 * k, 5, 0);
    chain.push_back(addBox(w, Vec3(0.15, 0.05, 0.05), 1.0, at));
    w.setBodyState(chain.back(), Transform(at, Quat::Identity()), Vec3(-cap, 0, 0), Vec3::Zero());
    if (k > 0) joints.push_back(chainLink(w, chain[k - 1], chain[k], 0.15));
  }
  std::vector<BodyFault> faults;
  for (int i = 0; i < 100; ++i) {
    w.step(kDt);
    ASSERT_LE(farthest(w), kWorldRange) << "step " << i;
    for (const BodyFault& f : w.takeBodyFaults()) faults.push_back(f);
  }
  ASSERT_FALSE(faults.empty());
  bool free_reset = false;
  for (const BodyFault& f : faults) {
    EXPECT_EQ(f.cause, BodyFaultCause::OutOfRange) << "body " << f.body.index;
    free_reset |= f.body == free;
  }
  EXPECT_TRUE(free_reset);
  EXPECT_EQ(w.bodyFaultCount(), int64_t(faults.size()));
  const BodyState s = w.bodyState(free);
  EXPECT_EQ(s.linear_velocity, Vec3::Zero());
  EXPECT_EQ(s.angular_velocity, Vec3::Zero());
  EXPECT_GT(s.com_position.x(), edge) << "reset to its last pose in range, not to the start";
  for (JointId j : joints) EXPECT_LT(w.jointAnchorError(j).norm(), 0.01);
}

// setBodyState beyond the range (a 1e160 m coordinate is finite: the non-finite check lets it
// through) is undone before the step: the body is back at its last pose in range.
TEST(BodyFaults, BodyStateBeyondTheWorldRangeIsAnInputFault) {
  World w;
  const BodyId b = addDynamic(w, 1.0, Mat3::Identity() * 0.1,
                              Transform(Vec3(1, 2, 3), Quat::Identity()));
  w.step(kDt);
  const Vec3 before = w.comPosition(b);
  for (const Vec3& far : {Vec3(1e160, 0, 0), Vec3(0, -2 * kWorldRange, 0),
                          Vec3(0, 0, kWorldRange + 1.0)}) {
    w.setBodyState(b, Transform(far, Quat::Identity()), Vec3(1, 0, 0), Vec3::Zero());
    w.step(kDt);
    const std::vector<BodyFault> faults = w.takeBodyFaults();
    ASSERT_EQ(faults.size(), 1u) << far.transpose();
    EXPECT_EQ(faults[0].cause, BodyFaultCause::OutOfRange);
    EXPECT_LT((w.comPosition(b) - before).norm(), 1e-4) << far.transpose();
    EXPECT_LE(farthest(w), kWorldRange);
  }
  EXPECT_EQ(w.bodyFaultCount(), 3);
  BodyDef d;
  d.pose.p = Vec3(0, 0, 1.5 * kWorldRange);
  EXPECT_THROW(w.createBody(d), std::invalid_argument) << "created beyond the range";
}
