// World::breakJoint (restoring a state with broken joints): the joint
// stops acting at once, exactly like one that broke under load, without an event.
#include <gtest/gtest.h>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;

TEST(BreakJoint, ReleasesTheBodyWithoutAnEvent) {
  const double g = 9.81, dt = 1e-3;
  World w;
  FixedJointDef f;
  f.body_a = test::addStatic(w);
  f.body_b = test::addDynamic(w, 2.0, Vec3(0.02, 0.02, 0.005).asDiagonal(),
                              Transform(Vec3(0, 0, 1), Quat::Identity()), Vec3(0, 0, -0.3));
  f.frame_a.p = Vec3(0, 0, 1);
  const JointId j = w.createFixedJoint(f);  // unbreakable
  for (int i = 0; i < 100; ++i) w.step(dt);
  EXPECT_FALSE(w.isJointBroken(j));
  EXPECT_LT(w.bodyState(f.body_b).linear_velocity.norm(), 1e-6) << "held by the weld";

  w.breakJoint(j);
  w.breakJoint(j);  // twice is harmless
  EXPECT_TRUE(w.isJointBroken(j));
  EXPECT_TRUE(w.takeBrokenJoints().empty()) << "no event for a joint broken by hand";
  const double v0 = w.bodyState(f.body_b).linear_velocity.z();
  for (int i = 0; i < 100; ++i) w.step(dt);
  EXPECT_NEAR(w.bodyState(f.body_b).linear_velocity.z() - v0, -g * 0.1, 1e-9) << "free fall";
}
