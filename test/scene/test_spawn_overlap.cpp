// A ragdoll placed into static geometry (SceneDef::spawn_overlap): the bundled ragdoll spawned
// below the ground or with its legs in it is lifted to rest on it with a WARN, and then falls
// and settles like any other (no body faults, nothing thrown away); with Refuse the spawn is
// refused with a message; reset and set_ragdoll_state lift too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "ragdoll_sim/scene.hpp"
#include "scene_recorder.hpp"
#include "ragdoll_sim/urdf_loader.hpp"

using namespace ragdoll_sim;

namespace {

using test::Recorder;

RagdollDef bundled() {
  const UrdfLoadResult r = loadUrdfFile(std::string(RAGDOLL_SIM_SOURCE_DIR) + "/urdf/ragdoll.urdf");
  EXPECT_TRUE(r.ok) << r.error;
  return r.def;
}

SpawnDef spawnAt(const std::string& name, const Vec3& p, const Quat& q = Quat::Identity()) {
  SpawnDef s;
  s.name = name;
  s.def = bundled();
  s.pose = Transform(p, q);
  return s;
}

// Height of the lowest point of the shape g at pose x (the shapes the bundled ragdoll has).
double lowestZ(const Geometry& g, const Transform& x) {
  const Mat3 R = x.q.toRotationMatrix();
  const double cz = x.p.z();
  switch (g.type) {
    case ShapeType::Sphere: return cz - g.radius;
    case ShapeType::Box: return cz - R.row(2).cwiseAbs().dot(g.half_extents);
    case ShapeType::Capsule: return cz - g.half_height * std::abs(R(2, 2)) - g.radius;
    case ShapeType::Cylinder: {
      const double az = std::abs(R(2, 2));
      return cz - g.half_height * az - g.radius * std::sqrt(std::max(0.0, 1 - az * az));
    }
    default: ADD_FAILURE() << "shape type not handled"; return cz;
  }
}

// Lowest shape point and highest link origin of ragdoll k.
struct Extent {
  double lowest = 1e300, highest = -1e300;
};
Extent extent(const Scene& scene, int k) {
  Extent e;
  for (BodyId b : scene.bodies(k).bodies) {
    const Transform pose = scene.world().bodyPose(b);
    e.highest = std::max(e.highest, pose.p.z());
    for (const ShapeDef& s : scene.world().bodyShapes(b))
      e.lowest = std::min(e.lowest, lowestZ(s.geometry, pose * s.local));
  }
  return e;
}

}  // namespace

// z = -1 and -50: the whole ragdoll below the ground; z = 0: pelvis on it, legs in it; prone
// at z = -1. Each is lifted so that its lowest point rests on the ground (within a mm), says
// so in a WARN that names it and the lift, and then falls and settles for 3 s with no body
// fault and every link within a few metres of the ground.
TEST(SpawnOverlap, RagdollSpawnedIntoTheGroundIsLiftedOntoIt) {
  struct Case {
    Vec3 at;
    Quat q;
  };
  for (const Case& c : {Case{Vec3(0, 0, -1), Quat::Identity()},
                        Case{Vec3(3, 0, -50), Quat::Identity()},
                        Case{Vec3(0, 3, 0), Quat::Identity()},
                        Case{Vec3(0, 0, -1), quatFromRpy(0, M_PI / 2, 0.3)}}) {
    SCOPED_TRACE("spawned at z = " + std::to_string(c.at.z()));
    Recorder log;
    Scene scene(SceneDef(), &log);
    std::string e;
    ASSERT_TRUE(scene.start(&e)) << e;
    ASSERT_EQ(scene.addRagdoll(spawnAt("low", c.at, c.q), &e), SpawnResult::Added) << e;
    const Extent at_spawn = extent(scene, 0);
    EXPECT_NEAR(at_spawn.lowest, 0.0, 1e-3) << "lowest point not on the ground";
    const SceneMessage* warn = log.find("spawn/lifted");
    ASSERT_NE(warn, nullptr) << "no WARN";
    EXPECT_EQ(warn->level, SceneMessage::Level::Warn);
    EXPECT_NE(warn->text.find("'low'"), std::string::npos) << warn->text;
    EXPECT_NE(warn->text.find("lifted"), std::string::npos) << warn->text;
    EXPECT_NE(warn->text.find("'ground'"), std::string::npos) << warn->text;
    std::printf("[ lifted   ] %s\n", warn->text.c_str());
    double highest = -1e300;
    for (int i = 0; i < 3000; ++i) {
      scene.step();
      highest = std::max(highest, extent(scene, 0).highest);
    }
    EXPECT_EQ(scene.counters().body_faults, 0u);
    EXPECT_EQ(scene.world().bodyFaultCount(), 0);
    EXPECT_LT(highest, 3.0) << "a link was thrown up";
    const Extent end = extent(scene, 0);
    EXPECT_GT(end.lowest, -0.01) << "sank into the ground";
    for (BodyId b : scene.bodies(0).bodies)
      EXPECT_LT(scene.world().bodyPose(b).p.head<2>().norm() - c.at.head<2>().norm(), 3.0);
  }
}

// The lifted pose is the ragdoll's spawn pose: reset brings it back there, with no new WARN.
// set_ragdoll_state into the ground lifts it as well.
TEST(SpawnOverlap, ResetAndMovesKeepItOutOfTheGround) {
  Recorder log;
  Scene scene(SceneDef(), &log);
  std::string e;
  ASSERT_EQ(scene.addRagdoll(spawnAt("low", Vec3(0, 0, -1)), &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;  // a ragdoll added before start is checked at start
  EXPECT_NEAR(extent(scene, 0).lowest, 0.0, 1e-3);
  ASSERT_NE(log.find("spawn/lifted"), nullptr);
  for (int i = 0; i < 500; ++i) scene.step();
  log.messages.clear();
  ASSERT_TRUE(scene.reset(&e)) << e;
  EXPECT_NEAR(extent(scene, 0).lowest, 0.0, 1e-3);
  EXPECT_EQ(log.find("reset/lifted"), nullptr) << "the spawn pose was not kept lifted";

  scene.setRagdollState(0, Transform(Vec3(1, 0, -0.5), Quat::Identity()), Vec3(1, 0, 0),
                        Vec3::Zero());
  EXPECT_NEAR(extent(scene, 0).lowest, 0.0, 1e-3);
  ASSERT_NE(log.find("set_ragdoll_state/lifted"), nullptr);
  const BodyState s = scene.world().bodyState(scene.bodies(0).bodies[0]);
  EXPECT_NEAR(s.linear_velocity.x(), 1.0, 1e-9) << "the lift keeps the velocity";
  for (int i = 0; i < 2000; ++i) scene.step();
  EXPECT_EQ(scene.counters().body_faults, 0u);

  // Resting on the ground it sinks a little into it: its own pose set again is no overlap.
  log.messages.clear();
  const Transform rest = scene.world().bodyPose(scene.bodies(0).bodies[0]);
  scene.setRagdollState(0, rest, Vec3::Zero(), Vec3::Zero());
  EXPECT_EQ(log.find("set_ragdoll_state/lifted"), nullptr) << log.messages[0].text;
}

// spawn_overlap = Refuse: a spawn into the ground is refused with a message that names the
// ragdoll, the depth and the rule, and leaves no body behind; one clear of it is added. A
// ragdoll added before start makes start fail the same way.
TEST(SpawnOverlap, RefuseOptionRefusesWithAMessage) {
  SceneDef def;
  def.spawn_overlap = SpawnOverlap::Refuse;
  {
    Scene scene(def);
    std::string e;
    ASSERT_TRUE(scene.start(&e)) << e;
    const int bodies = scene.world().bodyCount();
    EXPECT_EQ(scene.addRagdoll(spawnAt("low", Vec3(0, 0, -1)), &e), SpawnResult::WorldRefused);
    EXPECT_NE(e.find("'low'"), std::string::npos) << e;
    EXPECT_NE(e.find("refused"), std::string::npos) << e;
    EXPECT_NE(e.find("spawn_overlap"), std::string::npos) << e;
    EXPECT_EQ(scene.ragdollCount(), 0u);
    for (int b = bodies; b < scene.world().bodyCount(); ++b)
      EXPECT_FALSE(scene.world().isValid(BodyId{b})) << "body " << b << " left behind";
    EXPECT_EQ(scene.addRagdoll(spawnAt("high", Vec3(0, 0, 1.2)), &e), SpawnResult::Added) << e;
  }
  {
    Scene scene(def);
    std::string e;
    ASSERT_EQ(scene.addRagdoll(spawnAt("low", Vec3(0, 0, 0)), &e), SpawnResult::Added) << e;
    EXPECT_FALSE(scene.start(&e));
    EXPECT_NE(e.find("'low'"), std::string::npos) << e;
    EXPECT_NE(e.find("spawn_overlap"), std::string::npos) << e;
  }
}
