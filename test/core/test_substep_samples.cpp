// Substep velocity samples of tracked bodies (World::trackBody, SubstepVelocities): free fall
// changes each sample by g h, a sleeping body gets equal samples, the last sample is the
// velocity the step ends with, and tracking changes no result, on one or two threads.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1e-3;

bool sameBits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0; }
}  // namespace

TEST(SubstepSamples, FreeFallChangesEachSampleByGravityTimesH) {
  World w;
  const BodyId ball = addSphere(w, 0.1, 4.0, Vec3(0, 0, 10), Material());
  SubstepVelocities s;
  EXPECT_FALSE(w.substepVelocities(ball, &s));  // not tracked
  w.trackBody(ball, true);
  EXPECT_FALSE(w.substepVelocities(ball, &s));  // no step since
  for (int i = 0; i < 3; ++i) w.step(kDt);
  ASSERT_TRUE(w.substepVelocities(ball, &s));
  const int n = w.def().solver.substeps;
  ASSERT_EQ(int(s.linear.size()), n);
  ASSERT_EQ(int(s.angular.size()), n);
  EXPECT_DOUBLE_EQ(s.h, kDt / n);
  const Vec3 gh = w.def().gravity * s.h;
  Vec3 prev = s.start_linear;
  EXPECT_NEAR(prev.z(), 2 * kDt * w.def().gravity.z(), 1e-12);
  for (int k = 0; k < n; ++k) {
    EXPECT_NEAR((s.linear[k] - prev - gh).norm(), 0.0, 1e-12) << "substep " << k;
    prev = s.linear[k];
  }
  EXPECT_TRUE(sameBits(s.linear.back(), w.bodyState(ball).linear_velocity));
  w.trackBody(ball, false);
  EXPECT_FALSE(w.substepVelocities(ball, &s));
  EXPECT_THROW(w.trackBody(BodyId{99}, true), std::out_of_range);
}

// Asleep (the settled world's short step too) and static bodies: `substeps` equal samples.
TEST(SubstepSamples, SleepingAndStaticBodiesGetEqualSamples) {
  World w;
  const BodyId ground = addGround(w);
  const BodyId box = addBox(w, Vec3(0.2, 0.2, 0.1), 2.0, Vec3(0, 0, 0.1));
  w.trackBody(box, true);
  w.trackBody(ground, true);
  for (int i = 0; i < 5000 && w.isAwake(box); ++i) w.step(kDt);
  ASSERT_FALSE(w.isAwake(box));
  for (int i = 0; i < 2; ++i) {  // the step that finds it asleep, then a settled one
    w.step(kDt);
    for (const BodyId b : {box, ground}) {
      SubstepVelocities s;
      ASSERT_TRUE(w.substepVelocities(b, &s));
      ASSERT_EQ(int(s.linear.size()), w.def().solver.substeps);
      for (size_t k = 0; k < s.linear.size(); ++k) {
        EXPECT_TRUE(sameBits(s.linear[k], s.start_linear));
        EXPECT_TRUE(sameBits(s.angular[k], s.start_angular));
      }
    }
  }
  w.destroyBody(box);
  SubstepVelocities s;
  EXPECT_FALSE(w.substepVelocities(box, &s));
}

// A bouncing ball: the substep before the bounce still falls, the last sample (after
// restitution) rises with the velocity the step ends with.
TEST(SubstepSamples, LastSampleIncludesRestitution) {
  World w;
  Material bouncy;
  bouncy.restitution = 0.8;
  addGround(w, bouncy);
  const BodyId ball = addSphere(w, 0.1, 1.0, Vec3(0, 0, 0.6), bouncy);
  w.trackBody(ball, true);
  bool bounced = false;
  for (int i = 0; i < 1000 && !bounced; ++i) {
    w.step(kDt);
    SubstepVelocities s;
    ASSERT_TRUE(w.substepVelocities(ball, &s));
    if (s.start_linear.z() < -1.0 && s.linear.back().z() > 1.0) {
      bounced = true;
      EXPECT_TRUE(sameBits(s.linear.back(), w.bodyState(ball).linear_velocity));
      EXPECT_NEAR(s.linear.back().z(), -0.8 * s.start_linear.z(), 0.1 * -s.start_linear.z());
    }
  }
  EXPECT_TRUE(bounced);
}

namespace {
// 8 chains of 8 boxes meeting in zero gravity (one island of 64 bodies, split), ball joints.
std::unique_ptr<World> raft(int threads, std::vector<BodyId>* boxes) {
  WorldDef def;
  def.gravity.setZero();
  def.sleep.enabled = false;
  def.threads = threads;
  auto w = std::make_unique<World>(def);
  const double half = 0.1;
  Material bouncy;
  bouncy.restitution = 0.5;
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < 8; ++k) {
      const Vec3 v(0, c % 2 ? 0.8 : -0.8, 0.05 * c);
      const BodyId b = addBody(*w, Geometry::box(Vec3::Constant(half)), 1.0 + 0.1 * k,
                               boxInertia(Vec3::Constant(half), 1.0 + 0.1 * k),
                               Transform(Vec3(2 * half * k, 2 * half * c, 0), Quat::Identity()),
                               bouncy, v);
      if (k > 0) chainLink(*w, boxes->back(), b, half);
      boxes->push_back(b);
    }
  return w;
}
}  // namespace

// Tracking only reads: the same poses bit for bit with and without it, and the same samples
// on one and two threads, for bodies in both halves of a split island.
TEST(SubstepSamples, TrackingChangesNothingAndMatchesAcrossThreads) {
  std::vector<BodyId> b0, b1, b2;
  auto plain = raft(1, &b0), one = raft(1, &b1), two = raft(2, &b2);
  const std::vector<int> tracked = {0, 7, 20, 40, 63};
  for (int i : tracked) {
    one->trackBody(b1[i], true);
    two->trackBody(b2[i], true);
  }
  bool split = false;
  int changed = 0;
  for (int step = 0; step < 40; ++step) {
    plain->step(kDt);
    one->step(kDt);
    two->step(kDt);
    split |= one->islandCounters().split_islands > 0;
    for (int i : tracked) {
      SubstepVelocities s1, s2;
      ASSERT_TRUE(one->substepVelocities(b1[i], &s1));
      ASSERT_TRUE(two->substepVelocities(b2[i], &s2));
      ASSERT_EQ(s1.linear.size(), s2.linear.size());
      for (size_t k = 0; k < s1.linear.size(); ++k) {
        ASSERT_TRUE(sameBits(s1.linear[k], s2.linear[k])) << "body " << i << " step " << step;
        ASSERT_TRUE(sameBits(s1.angular[k], s2.angular[k]));
      }
      changed += !sameBits(s1.linear.front(), s1.start_linear);
    }
  }
  EXPECT_TRUE(split);
  EXPECT_GT(changed, 0);
  for (size_t i = 0; i < b0.size(); ++i) {
    const BodyState p = plain->bodyState(b0[i]), s = one->bodyState(b1[i]);
    EXPECT_TRUE(sameBits(p.com_position, s.com_position)) << "body " << i;
    EXPECT_TRUE(sameBits(p.linear_velocity, s.linear_velocity)) << "body " << i;
  }
}
