// Unit tests of the Scene (include/ragdoll_sim/scene.hpp): ragdolls by name, the command queue,
// timed forces, joint targets, removal and reset, without ROS.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "ragdoll_sim/scene.hpp"
#include "scene_recorder.hpp"
#include "scene_views.hpp"

using namespace ragdoll_sim;

namespace {

using test::Recorder;

SceneDef zeroGravity() {
  SceneDef d;
  d.world.gravity = Vec3::Zero();
  return d;
}

SpawnDef stick(const std::string& name, double y, double z = 1.0) {
  SpawnDef s;
  s.name = name;
  s.def = test::stickModel();
  s.pose = Transform(Vec3(0, y, z), Quat::Identity());
  return s;
}

Vec3 pelvis(const Scene& scene, int k) {
  return scene.world().bodyPose(scene.bodies(k).bodies[0]).p;
}

void start(Scene& scene, std::vector<SpawnDef> spawns) {
  std::string e;
  for (SpawnDef& s : spawns) ASSERT_EQ(scene.addRagdoll(std::move(s), &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
}

TEST(Scene, RagdollsFallAndTimeCountsInNanoseconds) {
  Scene scene{SceneDef()};
  start(scene, {stick("a", 0.0), stick("b", 2.0)});
  EXPECT_EQ(scene.ragdollCount(), 2u);
  EXPECT_EQ(scene.find("b"), 1);
  EXPECT_EQ(scene.find(""), 0);
  EXPECT_EQ(scene.find("c"), -1);
  for (int i = 0; i < 100; ++i) scene.step();
  EXPECT_EQ(scene.timeNs(), 100 * 1000000);
  EXPECT_EQ(scene.steps(), 100);
  EXPECT_LT(pelvis(scene, 0).z(), 0.99);
}

TEST(Scene, NameInUseIsRefused) {
  Scene scene{SceneDef()};
  start(scene, {stick("a", 0.0)});
  std::string e;
  EXPECT_EQ(scene.addRagdoll(stick("a", 2.0), &e), SpawnResult::NameInUse);
  EXPECT_NE(e.find("exists"), std::string::npos);
  EXPECT_EQ(scene.addRagdoll(stick("b", 2.0), &e), SpawnResult::Added) << e;
  EXPECT_EQ(scene.ragdollCount(), 2u);
}

TEST(Scene, CommandWaitsForItsSimTime) {
  Recorder rec;
  Scene scene(zeroGravity(), &rec);
  start(scene, {stick("a", 0.0)});
  ImpulseCommand c;
  c.link = "pelvis";
  c.point = pelvis(scene, 0);
  c.impulse = Vec3(10, 0, 0);
  ASSERT_TRUE(scene.submit("a", c, 5000000));
  for (int i = 0; i < 5; ++i) scene.step();
  EXPECT_EQ(scene.counters().applied, 0u);
  EXPECT_EQ(scene.counters().queued, 1u);
  scene.step();  // starts at 5 ms: applied first
  EXPECT_EQ(scene.counters().applied, 1u);
  EXPECT_EQ(rec.impulses, 1);
  EXPECT_GT(scene.world().bodyState(scene.bodies(0).bodies[0]).linear_velocity.x(), 0.0);
}

TEST(Scene, BadCommandsAreRejectedWithTheirKind) {
  Recorder rec;
  Scene scene(zeroGravity(), &rec);
  start(scene, {stick("a", 0.0)});
  ImpulseCommand c;
  c.link = "pelvis";
  EXPECT_FALSE(scene.submit("nobody", c, 0));
  EXPECT_TRUE(rec.saw("impulse/unknown ragdoll"));
  c.link = "nose";
  EXPECT_TRUE(scene.submit("", c, 0));
  scene.applyDueCommands();
  EXPECT_TRUE(rec.saw("impulse/unknown link"));
  scene.reject("target pose/two ragdolls", "two ragdolls");
  const SceneCounters n = scene.counters();
  EXPECT_EQ(n.received, 3u);
  EXPECT_EQ(n.rejected, 3u);
  EXPECT_EQ(n.applied, 0u);
}

TEST(Scene, TimedForceActsForItsDuration) {
  Recorder rec;
  Scene scene(zeroGravity(), &rec);
  start(scene, {stick("a", 0.0)});
  ForceCommand f;
  f.link = "pelvis";
  f.frame = "link";
  f.force = Vec3(0, 0, 100);
  f.duration = 0.01;  // 10 steps
  ASSERT_TRUE(scene.submit("a", f, 0));
  scene.step();
  EXPECT_EQ(scene.activeForceCount(), 1u);
  EXPECT_EQ(rec.forces, 1);
  for (int i = 0; i < 9; ++i) scene.step();
  EXPECT_EQ(scene.activeForceCount(), 0u);
  EXPECT_GT(pelvis(scene, 0).z(), 1.0);
  f.duration = -1.0;  // until cleared
  ASSERT_TRUE(scene.submit("a", f, 0));
  for (int i = 0; i < 20; ++i) scene.step();
  EXPECT_EQ(scene.clearForces(), 1u);
  EXPECT_EQ(scene.activeForceCount(), 0u);
}

TEST(Scene, TargetPoseDrivesTheJoint) {
  Scene scene{zeroGravity()};
  start(scene, {stick("a", 0.0)});
  ASSERT_EQ(scene.axisNames(0), std::vector<std::string>{"waist"});
  TargetPoseCommand t;
  t.names = {"waist"};
  t.position = {0.4};
  ASSERT_TRUE(scene.submit("a", t, 0));
  for (int i = 0; i < 500; ++i) scene.step();
  EXPECT_NEAR(scene.world().hingeAngle(scene.bodies(0).joints[0]), 0.4, 0.02);
  scene.clearTargets();
  EXPECT_EQ(scene.counters().applied, 1u);
}

TEST(Scene, RemoveKeepsTheOthersAndDropsTheirCommands) {
  Recorder rec;
  Scene scene(SceneDef(), &rec);
  start(scene, {stick("a", 0.0), stick("b", 2.0)});
  for (int i = 0; i < 50; ++i) scene.step();
  const Vec3 b = pelvis(scene, 1);
  ImpulseCommand c;
  c.link = "pelvis";
  ASSERT_TRUE(scene.submit("a", c, scene.timeNs() + 1000000));
  const RagdollId id = scene.id(1);
  std::string e;
  ASSERT_TRUE(scene.removeRagdoll("a", &e)) << e;
  EXPECT_FALSE(scene.removeRagdoll("a", &e));
  EXPECT_EQ(scene.ragdollCount(), 1u);
  EXPECT_EQ(scene.indexOf(id), 0);
  EXPECT_EQ(pelvis(scene, 0), b);
  scene.step();
  scene.step();
  EXPECT_TRUE(rec.saw("command/deleted ragdoll"));
}

// Removing a ragdoll, new solver settings and new friction change the World in place: a
// ragdoll asleep on the ground stays asleep with the same World ids, which a rebuilt World
// (every body created anew and awake) could not give.
TEST(Scene, RemovalAndSettingsDoNotRebuildTheWorld) {
  Scene scene{SceneDef()};
  start(scene, {stick("a", 0.0, 0.3), stick("b", 3.0, 0.3)});
  const World* world = &scene.world();
  for (int i = 0; i < 5000 && world->awakeBodyCount() > 0; ++i) scene.step();
  ASSERT_EQ(world->awakeBodyCount(), 0) << "the sticks never slept";
  const BodyId a0 = scene.bodies(0).bodies[0];
  const Transform pose = world->bodyPose(a0);
  std::string e;
  ASSERT_TRUE(scene.removeRagdoll("b", &e)) << e;
  {
    SolverSettings solver = scene.def().world.solver;
    solver.substeps = 4;
    solver.position_iterations = 2;
    std::string error;
    ASSERT_TRUE(scene.setSolverSettings(solver, &error)) << error;
  }
  scene.setMaterials(Material{0.9, 0.7, 0.1, 0.05}, MaterialTable());
  scene.step();
  EXPECT_EQ(scene.world().awakeBodyCount(), 0) << "removal or settings woke the sleeping ragdoll";
  ASSERT_EQ(&scene.world(), world) << "a new World";
  EXPECT_EQ(scene.bodies(0).bodies[0], a0);
  EXPECT_EQ(world->def().solver.substeps, 4);
  EXPECT_EQ(world->bodyShapes(a0)[0].material.static_friction, 0.9);
  EXPECT_EQ(world->bodyPose(a0).p, pose.p);
  // A spawn wakes only its own bodies.
  ASSERT_EQ(scene.addRagdoll(stick("c", -3.0), &e), SpawnResult::Added) << e;
  scene.step();
  EXPECT_EQ(world->awakeBodyCount(), int(scene.bodies(1).bodies.size()));
}

TEST(Scene, ResetGoesBackToTheSpawnPose) {
  Scene scene{SceneDef()};
  start(scene, {stick("a", 0.0)});
  const Vec3 spawn = pelvis(scene, 0);
  for (int i = 0; i < 100; ++i) scene.step();
  EXPECT_NE(pelvis(scene, 0), spawn);
  std::string e;
  ASSERT_TRUE(scene.reset(&e)) << e;
  EXPECT_EQ(pelvis(scene, 0), spawn);
}

TEST(Scene, SetStateMovesTheRagdollRigidly) {
  Scene scene{zeroGravity()};
  start(scene, {stick("a", 0.0)});
  scene.setRagdollState(0, Transform(Vec3(1, 2, 3), Quat::Identity()), Vec3(1, 0, 0), Vec3::Zero());
  const LinkState s = scene.linkState(0, 0);
  EXPECT_NEAR((s.pose.p - Vec3(1, 2, 3)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(s.linear_velocity.x(), 1.0, 1e-12);
  EXPECT_EQ(scene.findLink(0, "torso"), 1);
}

TEST(Scene, SameCommandsGiveTheSameSteps) {
  auto run = [] {
    Scene scene{SceneDef()};
    start(scene, {stick("a", 0.0)});
    ImpulseCommand c;
    c.link = "torso";
    c.frame = "link";
    c.impulse = Vec3(5, 0, 0);
    scene.submit("a", c, 20000000);
    for (int i = 0; i < 200; ++i) scene.step();
    return pelvis(scene, 0);
  };
  EXPECT_EQ(run(), run());
}

TEST(Scene, SettingsChangeBetweenSteps) {
  Scene scene{SceneDef()};
  start(scene, {stick("a", 0.0)});
  for (int i = 0; i < 10; ++i) scene.step();
  scene.setTimeStep(2000000);
  scene.step();
  EXPECT_EQ(scene.timeNs(), 12000000);
  {
    SolverSettings solver = scene.def().world.solver;
    solver.substeps = 4;
    solver.position_iterations = 2;
    std::string error;
    ASSERT_TRUE(scene.setSolverSettings(solver, &error)) << error;
  }
  EXPECT_EQ(scene.world().def().solver.substeps, 4);
  SolverSettings bad = scene.def().world.solver;
  bad.substeps = 0;
  std::string error;
  EXPECT_FALSE(scene.setSolverSettings(bad, &error));
  EXPECT_NE(error.find("substeps"), std::string::npos) << error;
  EXPECT_EQ(scene.def().world.solver.substeps, 4) << "a refused change must change nothing";
  scene.setMaterials(Material{0.5, 0.4, 0.0, 0.0}, MaterialTable());
  EXPECT_EQ(scene.def().ground_surface.static_friction, 0.5);
  scene.setGravity(Vec3::Zero());
  EXPECT_EQ(scene.world().def().gravity, Vec3::Zero());
}

TEST(Scene, BrokenJointsAreReportedByName) {
  SceneDef d;
  JointSettings weak;
  weak.break_force = 1.0;  // N: the torso's weight breaks it once the stick lands
  d.joints.emplace_back("waist", weak);
  Scene scene{d};
  start(scene, {stick("a", 0.0)});
  for (int i = 0; i < 1000 && scene.brokenJoints().empty(); ++i) scene.step();
  ASSERT_EQ(scene.brokenJoints().size(), 1u);
  const BrokenJointReport& b = scene.brokenJoints()[0];
  EXPECT_EQ(b.ragdoll, "a");
  EXPECT_EQ(b.joint, "waist");
  EXPECT_EQ(b.parent_link, "pelvis");
  EXPECT_EQ(b.child_link, "torso");
  EXPECT_EQ(b.break_force, 1.0);
  EXPECT_GE(b.force, 1.0);  // it breaks when the anchor force reaches break_force
  scene.step();
  EXPECT_TRUE(scene.brokenJoints().empty());
  std::string e;
  ASSERT_TRUE(scene.reset(&e)) << e;  // joints whole again
  EXPECT_FALSE(scene.world().isJointBroken(scene.bodies(0).joints[0]));
}

TEST(Scene, BalanceNamesWhatTheModelLacks) {
  Recorder rec;
  Scene scene(SceneDef(), &rec);
  start(scene, {stick("a", 0.0)});
  EXPECT_FALSE(scene.balanceOn(0));
  EXPECT_EQ(scene.balanceMissing(0), nullptr);
  scene.setBalance(true);
  EXPECT_TRUE(scene.balanceOn(0));
  ASSERT_NE(scene.balanceMissing(0), nullptr);
  EXPECT_FALSE(scene.balanceMissing(0)->empty());  // the stick has no ankles or feet
  EXPECT_FALSE(rec.messages.empty());
  for (int i = 0; i < 10; ++i) scene.step();
  scene.setBalance(false);
  EXPECT_EQ(scene.balanceMissing(0), nullptr);
}

}  // namespace
