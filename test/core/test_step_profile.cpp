// World::stepProfile: the phases of a step timed while profiling is on, zero while it is off,
// and no result changed by it.
#include <gtest/gtest.h>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1e-3;

// Boxes stacked two by two on the ground: contacts, pairs and an island every step.
std::vector<BodyId> boxScene(World& w) {
  addGround(w);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 4; ++i)
    boxes.push_back(addBox(w, Vec3(0.1, 0.1, 0.1), 1.0, Vec3(0.3 * (i % 2), 0, 0.1 + 0.2 * (i / 2))));
  return boxes;
}

bool allZero(const StepProfile& p) {
  return p.step == 0 && p.guard == 0 && p.collide == 0 && p.boxes == 0 && p.pairs == 0 &&
         p.narrowphase == 0 && p.islands == 0 && p.solve == 0 && p.finish == 0 &&
         p.solve_wait == 0;
}
}  // namespace

TEST(StepProfile, ZeroWhileProfilingIsOff) {
  World w;
  boxScene(w);
  for (int i = 0; i < 10; ++i) w.step(kDt);
  EXPECT_TRUE(allZero(w.stepProfile()));
  w.setProfiling(true);
  w.step(kDt);
  EXPECT_GT(w.stepProfile().step, 0.0);
  w.setProfiling(false);  // clears the last profile too
  EXPECT_TRUE(allZero(w.stepProfile()));
  w.step(kDt);
  EXPECT_TRUE(allZero(w.stepProfile()));
}

TEST(StepProfile, PhasesAddUpToTheStepAndCollideHoldsItsParts) {
  WorldDef def;
  def.sleep.enabled = false;
  World w(def);
  boxScene(w);
  w.setProfiling(true);
  for (int i = 0; i < 50; ++i) {
    w.step(kDt);
    const StepProfile& p = w.stepProfile();
    // every phase of a step with contacts took some time (the clock counts nanoseconds)
    for (double t : {p.guard, p.collide, p.boxes, p.pairs, p.narrowphase, p.islands, p.solve,
                     p.finish})
      EXPECT_GT(t, 0.0) << "step " << i;
    EXPECT_DOUBLE_EQ(p.step, p.guard + p.collide + p.islands + p.solve + p.finish);
    EXPECT_LE(p.boxes + p.pairs + p.narrowphase, p.collide * (1 + 1e-12)) << "step " << i;
  }
}

TEST(StepProfile, ASettledWorldOnlyGuardsAndFinishes) {
  World w;  // sleeping on
  boxScene(w);
  w.setProfiling(true);
  int steps = 0;
  while (w.awakeBodyCount() > 0 && steps < 5000) {
    w.step(kDt);
    ++steps;
  }
  ASSERT_EQ(w.awakeBodyCount(), 0) << "the boxes did not fall asleep";
  w.step(kDt);  // finds nobody awake: the pipeline runs once more
  w.step(kDt);  // settled: only the time moves
  const StepProfile& p = w.stepProfile();
  EXPECT_EQ(p.collide, 0.0);
  EXPECT_EQ(p.islands, 0.0);
  EXPECT_EQ(p.solve, 0.0);
  EXPECT_GT(p.step, 0.0);
  EXPECT_DOUBLE_EQ(p.step, p.guard + p.finish);
}

TEST(StepProfile, ProfilingChangesNoResult) {
  WorldDef def;
  def.sleep.enabled = false;
  World plain(def), timed(def);
  const std::vector<BodyId> a = boxScene(plain), b = boxScene(timed);
  timed.setProfiling(true);
  for (int i = 0; i < 300; ++i) {
    plain.step(kDt);
    timed.step(kDt);
  }
  for (size_t k = 0; k < a.size(); ++k) {
    const BodyState x = plain.bodyState(a[k]), y = timed.bodyState(b[k]);
    EXPECT_EQ(x.pose.p, y.pose.p);
    EXPECT_EQ(x.pose.q.coeffs(), y.pose.q.coeffs());
    EXPECT_EQ(x.linear_velocity, y.linear_velocity);
    EXPECT_EQ(x.angular_velocity, y.angular_velocity);
  }
}

// 64 boxes apart on the ground, each an island of its own: enough for both threads to take runs
// of them. Each thread's idle time in the solve's region is part of solve_wait: some on two
// threads (the region reaches the second thread late), at most the two threads' whole solve;
// none on one.
TEST(StepProfile, SolveWaitIsTheThreadsIdleTimeInTheSolve) {
  for (const int threads : {1, 2}) {
    WorldDef def;
    def.sleep.enabled = false;
    def.threads = threads;
    World w(def);
    addGround(w);
    for (int i = 0; i < 64; ++i)
      addBox(w, Vec3(0.1, 0.1, 0.1), 1.0, Vec3(0.5 * (i % 8), 0.5 * (i / 8), 0.1));
    w.setProfiling(true);
    double wait = 0.0, solve = 0.0;
    for (int i = 0; i < 20; ++i) {
      w.step(kDt);
      const StepProfile& p = w.stepProfile();
      EXPECT_GE(p.solve_wait, 0.0) << "step " << i;
      EXPECT_LE(p.solve_wait, threads * p.solve) << "step " << i;
      EXPECT_DOUBLE_EQ(p.step, p.guard + p.collide + p.islands + p.solve + p.finish);
      wait += p.solve_wait;
      solve += p.solve;
    }
    EXPECT_GT(solve, 0.0);
    if (threads == 1) EXPECT_EQ(wait, 0.0);
    else EXPECT_GT(wait, 0.0);
  }
}
