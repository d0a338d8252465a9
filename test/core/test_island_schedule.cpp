// The island schedule kept from step to step (WorldTuning::keep_schedule): a world that keeps
// it while nothing it is built from changed steps exactly as one that builds it every step,
// through every change that must rebuild it.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"
#include "world_tuning.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1e-3;

// Boxes falling into piles (contacts start and end touching, islands merge), a hinged chain
// whose breakable link snaps when a box lands on it, sleep on: the piles sleep and are woken
// by an impulse and by a box knocked into them; then bodies, joints, shapes and collision
// filters are made and removed while the rest is awake or asleep.
struct Scene {
  static constexpr int kLinks = 70, kWeak = 64;
  std::unique_ptr<World> w;
  std::vector<BodyId> boxes;  // pile p, level l: boxes[4 p + l]
  std::vector<BodyId> chain;
  JointId weak, added;
  BodyId late;

  Scene(bool keep, int threads) {
    WorldDef def;
    def.threads = threads;
    def.sleep.enabled = true;
    def.sleep.time = 0.3;
    w = std::make_unique<World>(def);
    WorldTuning tuning;
    tuning.keep_schedule = keep;
    WorldInternals::setTuning(*w, tuning);
    addGround(*w);
    const Vec3 half(0.1, 0.1, 0.1);
    for (int p = 0; p < 3; ++p)
      for (int l = 0; l < 4; ++l)
        boxes.push_back(addBox(*w, half, 1.0, Vec3(0.5 * p, 0.03 * l, 0.1 + 0.25 * l)));
    // A chain of kLinks lying on the ground, big enough to be split on two threads (kSplitMin
    // bodies), with a breakable joint near its end.
    for (int k = 0; k < kLinks; ++k)
      chain.push_back(addBox(*w, Vec3(0.1, 0.04, 0.04), 0.5, Vec3(3.0 + 0.2 * k, 0, 0.04)));
    for (int k = 0; k + 1 < kLinks; ++k) {
      HingeJointDef h;
      h.body_a = chain[k];
      h.body_b = chain[k + 1];
      h.frame_a.p = Vec3(0.1, 0, 0);
      h.frame_b.p = Vec3(-0.1, 0, 0);
      h.axis = Vec3::UnitY();
      if (k == kWeak) h.spring.break_force = 30.0;
      const JointId j = w->createHingeJoint(h);
      if (k == kWeak) weak = j;
    }
  }

  void step(int i) {
    if (i == 100) {  // a heavy box onto the chain's weak joint, from 0.5 m
      const Vec3 half(0.1, 0.1, 0.1);
      late = addBox(*w, half, 20.0, Vec3(3.1 + 0.2 * kWeak, 0, 0.6));
    }
    if (i == 700) w->applyLinearImpulseToCenter(boxes[3], Vec3(1.0, 0, 0));  // pile 0's top
    if (i == 900) w->applyLinearImpulseToCenter(boxes[8], Vec3(-4.0, 0, 0));  // into pile 1
    // Joints made and destroyed between awake bodies (woken a few steps before), so that only
    // the joint changes the schedule in that step.
    if (i == 1090 || i == 1290) {
      w->wake(boxes[8]);
      w->wake(boxes[9]);
    }
    if (i == 1100) {  // two boxes of pile 2 linked
      BallJointDef b;
      b.body_a = boxes[8];
      b.body_b = boxes[9];
      b.frame_a.p = Vec3(0, 0, 0.15);  // 5 cm apart: the joint pulls at once
      b.frame_b.p = Vec3(0, 0, -0.1);
      b.collide_connected = true;  // the pairs stay as they are
      added = w->createBallJoint(b);
    }
    if (i == 1300) w->destroyJoint(added);
    if (i == 1400) w->disableCollision(boxes[0], boxes[1]);
    if (i == 1500) w->wake(boxes[0]);
    if (i == 1700) w->removeShape(boxes[7], 0);
    if (i == 1900) w->destroyBody(boxes[5]);
    if (i == 2100) w->breakJoint(JointId{weak.index + 1});
    w->step(kDt);
  }
};

void expectSameState(const World& a, const World& b, int step) {
  ASSERT_EQ(a.awakeBodyCount(), b.awakeBodyCount()) << "step " << step;
  ASSERT_EQ(a.contacts().size(), b.contacts().size()) << "step " << step;
  for (int k = 0; k < a.bodyCount(); ++k) {
    const BodyId id{k};
    if (!a.isValid(id)) continue;
    const Transform x = a.bodyPose(id), y = b.bodyPose(id);
    ASSERT_EQ(std::memcmp(x.p.data(), y.p.data(), sizeof(double) * 3), 0) << "step " << step;
    ASSERT_EQ(std::memcmp(x.q.coeffs().data(), y.q.coeffs().data(), sizeof(double) * 4), 0)
        << "step " << step;
  }
}
}  // namespace

TEST(IslandSchedule, KeptScheduleStepsAsIfBuiltEveryStep) {
  for (const int threads : {1, 2}) {
    Scene kept(true, threads), built(false, threads);
    const int steps = 2500;
    int awake_steps = 0, mixed_steps = 0, split_steps = 0;
    for (int i = 0; i < steps; ++i) {
      kept.step(i);
      built.step(i);
      expectSameState(*kept.w, *built.w, i);
      if (HasFatalFailure()) return;
      const int awake = kept.w->awakeBodyCount();
      awake_steps += awake > 0;
      mixed_steps += awake > 0 && awake < kept.w->bodyCount() - 1;  // less the ground
      split_steps += kept.w->islandCounters().split_islands > 0;
    }
    EXPECT_TRUE(kept.w->isJointBroken(kept.weak)) << "the landing box broke the weak joint";
    const int64_t kept_builds = WorldInternals::scheduleBuilds(*kept.w);
    const int64_t built_builds = WorldInternals::scheduleBuilds(*built.w);
    // Off, every step with a body awake builds it; on, most of those keep last step's.
    EXPECT_GE(built_builds, awake_steps);
    EXPECT_LT(4 * kept_builds, built_builds);
    EXPECT_GT(mixed_steps, 500) << "islands asleep beside awake ones";
    EXPECT_GT(split_steps, 500) << "the chain solved in two halves";
    std::printf("[ schedule ] %d thread(s): built %lld times in %d steps with bodies awake "
                "(%lld without keeping it; %d with sleepers, %d split)\n",
                threads, static_cast<long long>(kept_builds), awake_steps,
                static_cast<long long>(built_builds), mixed_steps, split_steps);
  }
}

// A step whose contacts are the last step's pairs (kept in place) but one of which starts
// touching must build the schedule again: the two boxes become one island.
TEST(IslandSchedule, PairStartingToTouchBuildsIt) {
  World w;
  addGround(w);
  const Vec3 half(0.1, 0.1, 0.1);
  addBox(w, half, 1.0, Vec3(0, 0, 0.1));
  // 5 cm above the lower box, beyond the speculative distance (2 cm): the boxes' pair is found
  // before its manifold has points, and it falls onto the box in ~100 ms.
  addBox(w, half, 1.0, Vec3(0, 0, 0.35));
  int64_t last = WorldInternals::scheduleBuilds(w);
  int rebuilt_while_kept_pairs = 0;
  bool touching = false;
  for (int i = 0; i < 300 && !touching; ++i) {
    const size_t pairs = WorldInternals::pairs(w).size();
    w.step(kDt);
    const int64_t now = WorldInternals::scheduleBuilds(w);
    for (const ContactInfo& c : w.contacts())  // the points of touching pairs
      if (c.body_a.index > 0 && c.body_b.index > 0) touching = true;
    if (touching) {
      EXPECT_EQ(WorldInternals::pairs(w).size(), pairs) << "the same pairs as the last step";
      rebuilt_while_kept_pairs += now > last;
    }
    last = now;
  }
  ASSERT_TRUE(touching);
  EXPECT_EQ(rebuilt_while_kept_pairs, 1);
}
