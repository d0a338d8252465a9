// Force budgets and caps of the Scene (src/scene/scene_forces.cpp): active forces are limited per
// ragdoll (one flooding publisher leaves the other ragdolls theirs) and over all ragdolls; the
// forces and torques on one link add up to at most max_body_force / max_body_torque each step.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ragdoll_sim/scene.hpp"
#include "scene_recorder.hpp"
#include "scene_views.hpp"

using namespace ragdoll_sim;

namespace {

using test::Recorder;

SpawnDef stick(const std::string& name, double y, double z = 1.0) {
  SpawnDef s;
  s.name = name;
  s.def = test::stickModel();  // pelvis 10 kg (inertia 0.1 kg m^2), torso 20 kg
  s.pose = Transform(Vec3(0, y, z), Quat::Identity());
  return s;
}

SceneDef zeroGravity() {
  SceneDef d;
  d.world.gravity = Vec3::Zero();
  return d;
}

void start(Scene& scene, std::vector<SpawnDef> spawns) {
  std::string e;
  for (SpawnDef& s : spawns) ASSERT_EQ(scene.addRagdoll(std::move(s), &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
}

ForceCommand upForce(double newtons, double duration = -1.0) {
  ForceCommand f;
  f.link = "pelvis";
  f.frame = "world";
  f.force = Vec3(0, 0, newtons);
  f.duration = duration;
  return f;
}

// Submits n forces for `ragdoll` and applies them; returns how many were applied.
uint64_t push(Scene& scene, const std::string& ragdoll, int n, const ForceCommand& f) {
  const uint64_t before = scene.counters().forces;
  for (int i = 0; i < n; ++i) scene.submit(ragdoll, f, 0);
  scene.applyDueCommands();
  return scene.counters().forces - before;
}

BodyState pelvisState(const Scene& scene, int k) {
  return scene.world().bodyState(scene.bodies(k).bodies[0]);
}

}  // namespace

TEST(ForceLimits, OneRagdollAtItsLimitLeavesTheOthersTheirForces) {
  Recorder rec;
  Scene scene(zeroGravity(), &rec);
  start(scene, {stick("a", 0.0), stick("b", 2.0)});
  const int per = SceneDef().max_forces_per_ragdoll;
  EXPECT_EQ(push(scene, "a", 300, upForce(1.0)), static_cast<uint64_t>(per));
  EXPECT_EQ(scene.activeForceCount(), static_cast<size_t>(per));
  const SceneMessage* w = rec.find("force/too many on one ragdoll");
  ASSERT_NE(w, nullptr);
  EXPECT_NE(w->text.find("ragdoll 'a' already has 64 active forces"), std::string::npos) << w->text;
  EXPECT_EQ(push(scene, "b", 10, upForce(1.0)), 10u) << "ragdoll b starved by ragdoll a";
  EXPECT_EQ(scene.counters().active_forces, static_cast<size_t>(per + 10));
  EXPECT_EQ(scene.counters().rejected, 300u - static_cast<uint64_t>(per));
}

TEST(ForceLimits, AllRagdollsTogetherHaveAGlobalBound) {
  Recorder rec;
  SceneDef def = zeroGravity();
  def.max_forces_per_ragdoll = 64;
  def.max_active_forces = 100;
  Scene scene(def, &rec);
  start(scene, {stick("a", 0.0), stick("b", 2.0)});
  EXPECT_EQ(push(scene, "a", 64, upForce(1.0)), 64u);
  EXPECT_EQ(push(scene, "b", 64, upForce(1.0)), 36u);
  EXPECT_NE(rec.find("force/too many"), nullptr);
  EXPECT_EQ(scene.clearForces(), 100u);
  EXPECT_EQ(push(scene, "b", 1, upForce(1.0)), 1u) << "cleared forces free the budget";
}

TEST(ForceLimits, SummedForceOnABodyIsCapped) {
  Recorder rec;
  SceneDef def = zeroGravity();
  def.max_forces_per_ragdoll = 128;
  Scene scene(def, &rec);
  start(scene, {stick("a", 0.0)});
  ASSERT_EQ(push(scene, "a", 128, upForce(1e5)), 128u);  // each one within max_force
  scene.step();
  // The whole cap on the pelvis alone, as if the joint passed nothing on: the upper bound.
  const double cap_dv = def.limits.max_body_force / 10.0 * scene.dt();
  const double vz = pelvisState(scene, 0).linear_velocity.z();
  EXPECT_GT(vz, 0.0);
  EXPECT_LE(vz, cap_dv * 1.001) << "128 x 1e5 N summed past max_body_force";
  const SceneMessage* w = rec.find("force/body cap");
  ASSERT_NE(w, nullptr) << "no WARN about the capped sum";
  EXPECT_NE(w->text.find("'a/pelvis'"), std::string::npos) << w->text;
  EXPECT_NE(w->text.find("1.28e+07 N"), std::string::npos) << w->text;
  // Said once for this set of forces, not once a step.
  for (int i = 0; i < 10; ++i) scene.step();
  size_t said = 0;
  for (const SceneMessage& m : rec.messages) said += m.kind == "force/body cap";
  EXPECT_EQ(said, 1u);
}

TEST(ForceLimits, CappedForcesKeepTheRagdollLowForFourSeconds) {
  SceneDef def;  // with gravity and ground
  def.max_forces_per_ragdoll = 128;
  def.limits.max_body_force = 600.0;  // N: 20 m/s^2 on the 30 kg stick, 10.2 m/s^2 net upwards
  Scene scene(def);
  start(scene, {stick("a", 0.0)});
  ASSERT_EQ(push(scene, "a", 128, upForce(600.0)), 128u);
  for (int i = 0; i < 4000; ++i) scene.step();
  // Capped: 1 m + 0.5 * 10.2 * 4^2 = 82.6 m at most; uncapped the 76800 N fly it at the
  // speed cap (100 m/s) to ~400 m.
  const double z = scene.world().bodyPose(scene.bodies(0).bodies[0]).p.z();
  EXPECT_GT(z, 40.0);
  EXPECT_LT(z, 85.0);
}

TEST(ForceLimits, SummedTorqueOnABodyIsCapped) {
  Recorder rec;
  SceneDef def = zeroGravity();
  def.max_forces_per_ragdoll = 128;
  def.limits.max_body_torque = 10.0;
  Scene scene(def, &rec);
  start(scene, {stick("a", 0.0)});
  ForceCommand f = upForce(0.0);
  f.torque = Vec3(0, 0, 10.0);
  ASSERT_EQ(push(scene, "a", 128, f), 128u);
  scene.step();
  const double wz = pelvisState(scene, 0).angular_velocity.z();
  EXPECT_GT(wz, 0.0);
  EXPECT_LE(wz, 10.0 / 0.1 * scene.dt() * 1.001) << "128 x 10 N m summed past max_body_torque";
  EXPECT_NE(rec.find("force/body cap"), nullptr);
}

TEST(ForceLimits, OpposingForcesDoNotCancelPastTheCap) {
  SceneDef def = zeroGravity();
  def.limits.max_body_force = 100.0;
  Scene scene(def);
  start(scene, {stick("a", 0.0)});
  // Up at +x, down at -x of the pelvis: no net force, a spin of 2 x 1e4 N x 0.1 m uncapped.
  ForceCommand up = upForce(1e4), down = upForce(-1e4);
  up.frame = down.frame = "link";
  up.point = Vec3(0.1, 0, 0);
  down.point = Vec3(-0.1, 0, 0);
  scene.submit("a", up, 0);
  scene.submit("a", down, 0);
  scene.step();
  // Capped at 100 N in all: each 50 N, a torque of 10 N m on 0.1 kg m^2 (and more with the torso).
  const double w = pelvisState(scene, 0).angular_velocity.norm();
  EXPECT_LE(w, 10.0 / 0.1 * scene.dt() * 1.001);
  EXPECT_GT(w, 0.0);
}

TEST(ForceLimits, CountersCountImpulsesAndForcesApart) {
  Scene scene{zeroGravity()};
  start(scene, {stick("a", 0.0)});
  ImpulseCommand i;
  i.link = "pelvis";
  i.frame = "link";
  i.impulse = Vec3(1, 0, 0);
  scene.submit("a", i, 0);
  scene.submit("a", i, 0);
  scene.submit("a", upForce(1.0, 0.0), 0);
  scene.step();
  const SceneCounters c = scene.counters();
  EXPECT_EQ(c.applied, 3u);
  EXPECT_EQ(c.impulses, 2u);
  EXPECT_EQ(c.forces, 1u);
  EXPECT_EQ(c.active_forces, 0u) << "a one-step force is over";
}
