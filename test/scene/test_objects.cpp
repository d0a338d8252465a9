// Objects in the Scene (issue 56): world files loaded into it (static models as static objects,
// dynamic ones as objects, the world's plane as the ground), objects added and removed at run
// time under the ragdolls' names, refused with a message naming the problem, reset to their
// spawn pose; a crate dropped on a lying ragdoll.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "object_models.hpp"
#include "ragdoll_sim/scene.hpp"
#include "ragdoll_sim/world_file.hpp"
#include "scene_recorder.hpp"

using namespace ragdoll_sim;

namespace {

using test::boxObject;
using test::Recorder;

WorldFileDef loadSdf(const std::string& models, const std::string& extra = "") {
  const std::string xml = "<?xml version='1.0'?><sdf version='1.7'><world name='w'>" + extra +
                          models + "</world></sdf>";
  const WorldLoadResult r = loadWorldString(xml);
  EXPECT_TRUE(r.ok) << r.error;
  return r.def;
}

std::string boxModelSdf(const std::string& name, const Vec3& at, const Vec3& size, bool is_static,
                        const std::string& surface = "") {
  char pose[128], sz[96];
  std::snprintf(pose, sizeof pose, "<pose>%g %g %g 0 0 0</pose>", at.x(), at.y(), at.z());
  std::snprintf(sz, sizeof sz, "%g %g %g", size.x(), size.y(), size.z());
  return "<model name='" + name + "'><static>" + (is_static ? "true" : "false") + "</static>" +
         pose + "<link name='l'><inertial><mass>2</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy>"
         "<izz>0.1</izz></inertia></inertial><collision name='c'><geometry><box><size>" + sz +
         "</size></box></geometry>" + surface + "</collision></link></model>";
}

std::string sphereModelSdf(const std::string& name, const Vec3& at, double r) {
  char pose[128];
  std::snprintf(pose, sizeof pose, "<pose>%g %g %g 0 0 0</pose>", at.x(), at.y(), at.z());
  const double I = 0.4 * 1.0 * r * r;
  return "<model name='" + name + "'>" + pose + "<link name='l'><inertial><mass>1</mass><inertia>"
         "<ixx>" + std::to_string(I) + "</ixx><iyy>" + std::to_string(I) + "</iyy><izz>" +
         std::to_string(I) + "</izz></inertia></inertial><collision name='c'><geometry><sphere>"
         "<radius>" + std::to_string(r) + "</radius></sphere></geometry></collision></link></model>";
}

std::string planeModelSdf(const std::string& name, const Vec3& normal) {
  char n[96];
  std::snprintf(n, sizeof n, "%.9g %.9g %.9g", normal.x(), normal.y(), normal.z());
  return "<model name='" + name + "'><static>true</static><link name='link'><collision name='c'>"
         "<geometry><plane><normal>" + n + "</normal><size>100 100</size></plane></geometry>"
         "</collision></link></model>";
}

int countBodiesNamed(const World& w, const std::string& name) {
  int n = 0;
  for (int b = 0; b < w.bodyCount(); ++b)
    if (w.isValid(BodyId{b}) && w.bodyDef(BodyId{b}).name == name) ++n;
  return n;
}

void run(Scene& scene, double seconds) {
  const int n = int(std::lround(seconds / scene.dt()));
  for (int i = 0; i < n; ++i) scene.step();
}

Vec3 origin(const Scene& scene, int k, int link = 0) {
  return scene.world().bodyPose(scene.bodies(k).bodies[size_t(link)]).p;
}

TEST(SceneObjects, LoadWorldCountsStaticAndDynamicModels) {
  const WorldFileDef w = loadSdf(planeModelSdf("ground_plane", Vec3::UnitZ()) +
                                     boxModelSdf("table", Vec3(3, 0, 0.4), Vec3(1, 1, 0.8), true) +
                                     boxModelSdf("wall", Vec3(0, 5, 1), Vec3(4, 0.2, 2), true) +
                                     boxModelSdf("crate", Vec3(3, 0, 1.2), Vec3(0.4, 0.4, 0.4), false) +
                                     sphereModelSdf("ball", Vec3(-2, 0, 0.5), 0.1),
                                 "<gravity>0 0 -5</gravity>");
  for (bool before_start : {true, false}) {
    Scene scene{SceneDef()};
    std::string e;
    if (!before_start) {
      ASSERT_TRUE(scene.start(&e)) << e;
    }
    ASSERT_TRUE(scene.loadWorld(w, &e)) << e;
    if (before_start) {
      ASSERT_TRUE(scene.start(&e)) << e;
    }
    EXPECT_EQ(scene.staticObjectCount(), 3u);
    ASSERT_EQ(scene.ragdollCount(), 2u);
    EXPECT_TRUE(scene.isObject(0));
    EXPECT_TRUE(scene.isObject(1));
    EXPECT_EQ(scene.find(""), -1) << "objects are not the default ragdoll";
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(scene.staticObjectBodies(i).size(), 1u);
      EXPECT_TRUE(scene.world().isValid(scene.staticObjectBodies(i)[0]));
    }
    EXPECT_EQ(scene.def().world.gravity, Vec3(0, 0, -5));
    // The ball falls at the world's gravity: v = 5 m/s^2 * t.
    const int ball = scene.find("ball");
    ASSERT_GE(ball, 0);
    run(scene, 0.1);
    EXPECT_NEAR(scene.linkState(ball, 0).linear_velocity.z(), -0.5, 0.01);
    // The crate lands on the table (top at 0.8 m).
    run(scene, 1.5);
    EXPECT_NEAR(origin(scene, scene.find("crate")).z(), 1.0, 0.01);
  }
}

TEST(SceneObjects, WorldPlaneReplacesTheDefaultGround) {
  // A plane tilted 10 degrees about x: downhill is -y.
  const double a = 10.0 * M_PI / 180.0;
  const Vec3 n(0, -std::sin(a), std::cos(a));
  const WorldFileDef w = loadSdf(planeModelSdf("slope", n) + sphereModelSdf("ball", Vec3(0, 0, 1.0), 0.1));
  Scene scene{SceneDef()};
  std::string e;
  ASSERT_TRUE(scene.start(&e)) << e;
  ASSERT_EQ(countBodiesNamed(scene.world(), "ground"), 1);
  ASSERT_TRUE(scene.loadWorld(w, &e)) << e;
  EXPECT_EQ(countBodiesNamed(scene.world(), "ground"), 0) << "the default plane is still there";
  ASSERT_EQ(scene.staticObjectCount(), 1u);
  EXPECT_EQ(scene.ground(), scene.staticObjectBodies(0)[0]);
  run(scene, 2.0);
  const Vec3 p = origin(scene, scene.find("ball"));
  EXPECT_LT(p.y(), -1.0) << "the ball does not roll down the world's slope";
  EXPECT_NEAR(n.dot(p), 0.1, 0.01) << "the ball is not on the slope";
  // A rebuild keeps the world's ground and no default plane.
  ASSERT_TRUE(scene.reset(&e)) << e;
  EXPECT_EQ(countBodiesNamed(scene.world(), "ground"), 0);
  EXPECT_EQ(scene.ground(), scene.staticObjectBodies(0)[0]);
  // Removing the world's ground leaves none: the default plane does not come back.
  ASSERT_TRUE(scene.remove("slope", &e)) << e;
  EXPECT_FALSE(scene.ground().valid());
  ASSERT_TRUE(scene.reset(&e)) << e;
  EXPECT_FALSE(scene.ground().valid());
  EXPECT_EQ(countBodiesNamed(scene.world(), "ground"), 0);
}

TEST(SceneObjects, WorldWithoutPlaneKeepsTheDefaultGround) {
  const WorldFileDef w = loadSdf(boxModelSdf("crate", Vec3(0, 0, 1), Vec3(0.4, 0.4, 0.4), false));
  for (bool ground : {true, false}) {
    SceneDef sd;
    sd.ground = ground;
    Scene scene(sd);
    std::string e;
    ASSERT_TRUE(scene.loadWorld(w, &e)) << e;
    ASSERT_TRUE(scene.start(&e)) << e;
    EXPECT_EQ(scene.ground().valid(), ground);
    run(scene, 1.5);
    if (ground) {
      EXPECT_NEAR(origin(scene, 0).z(), 0.2, 0.01);
    } else {
      EXPECT_LT(origin(scene, 0).z(), -5.0);
    }
  }
}

// Joints to the world: a hinge holds the pendulum's bar at its pivot (a static anchor carries
// it), a weld pins its link where the file has it (a fixed base).
TEST(SceneObjects, JointsToTheWorldHoldModels) {
  const WorldLoadResult hinged =
      loadWorldFile(std::string(RAGDOLL_SIM_SOURCE_DIR) + "/test/world_file/fixtures/joints.world");
  ASSERT_TRUE(hinged.ok) << hinged.error;
  const WorldFileDef welded = loadSdf(
      "<model name='sign'><pose>3 0 2 0 0 0</pose><link name='board'><collision name='c'>"
      "<geometry><box><size>0.5 0.05 0.5</size></box></geometry></collision></link>"
      "<joint name='pin' type='fixed'><parent>world</parent><child>board</child></joint></model>");
  SceneDef sd;
  sd.ground = false;
  Scene scene(sd);
  std::string e;
  ASSERT_TRUE(scene.loadWorld(hinged.def, &e)) << e;
  ASSERT_TRUE(scene.loadWorld(welded, &e)) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  const int p = scene.find("pendulum"), s = scene.find("sign");
  ASSERT_GE(p, 0);
  ASSERT_GE(s, 0);
  const int bar = scene.findLink(p, "bar");
  ASSERT_GE(bar, 0);
  // Pushed sideways, the bar swings about its pivot at (0, 0, 2) instead of falling.
  const BodyId bar_body = scene.bodies(p).bodies[size_t(bar)];
  scene.world().applyLinearImpulseToCenter(bar_body, Vec3(20, 0, 0));
  double worst = 0.0;
  bool swung = false;
  for (int i = 0; i < 2000; ++i) {
    scene.step();
    const Transform x = scene.world().bodyPose(bar_body);
    worst = std::max(worst, (x.apply(Vec3(0, 0, 0.5)) - Vec3(0, 0, 2)).norm());
    swung = swung || std::abs(x.p.x()) > 0.1;
  }
  EXPECT_TRUE(swung);
  EXPECT_LT(worst, 0.005) << "the bar left its pivot";
  const Transform sign = scene.world().bodyPose(scene.bodies(s).bodies[0]);
  EXPECT_LT((sign.p - Vec3(3, 0, 2)).norm(), 1e-6) << "the welded sign fell";
  EXPECT_TRUE(scene.def(s).fixed_base);
}

// A world's model is left where its author put it (as Gazebo does, and without checking
// thousands of models against every static shape); a crate spawned at run time into a table is
// lifted onto it, with a WARN, whatever spawn_overlap says.
TEST(SceneObjects, WorldModelsStayWhereTheFilePutsThem) {
  const WorldFileDef w = loadSdf(boxModelSdf("table", Vec3(0, 0, 0.4), Vec3(1, 1, 0.8), true) +
                                 boxModelSdf("crate", Vec3(0, 0, 0.98), Vec3(0.4, 0.4, 0.4), false));
  Recorder rec;
  SceneDef sd;
  sd.spawn_overlap = SpawnOverlap::Refuse;
  Scene scene(sd, &rec);
  std::string e;
  ASSERT_TRUE(scene.loadWorld(w, &e)) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  EXPECT_NEAR(origin(scene, scene.find("crate")).z(), 0.98, 1e-9);
  ASSERT_EQ(scene.addObject(boxObject("box", Vec3(0.2, 0.2, 0.2), 1, Vec3(0.5, 0.5, 0.9)), &e),
            SpawnResult::Added) << e;
  EXPECT_NEAR(origin(scene, scene.find("box")).z(), 1.0, 1e-6) << "not lifted onto the table";
  EXPECT_NE(rec.find("spawn/lifted"), nullptr);
}

TEST(SceneObjects, WorldModelNamesBecomeSceneNames) {
  const WorldFileDef w = loadSdf(boxModelSdf("cafe-table", Vec3(0, 0, 0.4), Vec3(1, 1, 0.8), true) +
                                 boxModelSdf("cafe_table", Vec3(3, 0, 0.4), Vec3(1, 1, 0.8), true) +
                                 boxModelSdf("2box", Vec3(0, 0, 2), Vec3(0.2, 0.2, 0.2), false));
  Recorder rec;
  Scene scene(SceneDef(), &rec);
  std::string e;
  ASSERT_TRUE(scene.loadWorld(w, &e)) << e;
  ASSERT_EQ(scene.staticObjectCount(), 2u);
  EXPECT_EQ(scene.staticObjectName(0), "cafe_table");
  EXPECT_EQ(scene.staticObjectName(1), "cafe_table_2");
  EXPECT_GE(scene.find("m_2box"), 0);
  bool said = false;
  for (const SceneMessage& m : rec.messages) said = said || m.text.find("'cafe-table'") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(SceneObjects, NamesAreOneNamespace) {
  Recorder rec;
  Scene scene(SceneDef(), &rec);
  std::string e;
  SpawnDef r = boxObject("crate", Vec3(0.1, 0.1, 0.1), 1.0, Vec3(0, 0, 1));
  r.def = test::bundledRagdoll();
  ASSERT_EQ(scene.addRagdoll(r, &e), SpawnResult::Added) << e;
  ASSERT_EQ(scene.addObject(boxObject("wall", Vec3(1, 0.1, 1), 1, Vec3(0, 3, 1), true), &e),
            SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  const int bodies = scene.world().bodyCount();
  // A world whose model has the ragdoll's name: refused whole, naming it.
  const WorldFileDef w = loadSdf(boxModelSdf("table", Vec3(5, 0, 0.4), Vec3(1, 1, 0.8), true) +
                                 boxModelSdf("crate", Vec3(5, 0, 1.2), Vec3(0.4, 0.4, 0.4), false));
  EXPECT_FALSE(scene.loadWorld(w, &e));
  EXPECT_NE(e.find("'crate'"), std::string::npos) << e;
  EXPECT_EQ(scene.staticObjectCount(), 1u);
  EXPECT_EQ(scene.ragdollCount(), 1u);
  EXPECT_EQ(scene.world().bodyCount(), bodies);
  EXPECT_EQ(scene.addObject(boxObject("crate", Vec3(0.1, 0.1, 0.1), 1, Vec3(3, 0, 1)), &e),
            SpawnResult::NameInUse);
  EXPECT_NE(e.find("ragdoll named 'crate'"), std::string::npos) << e;
  SpawnDef again = r;
  again.name = "wall";
  EXPECT_EQ(scene.addRagdoll(again, &e), SpawnResult::NameInUse);
  EXPECT_NE(e.find("static object named 'wall'"), std::string::npos) << e;
  EXPECT_EQ(scene.addObject(boxObject("wall", Vec3(0.1, 0.1, 0.1), 1, Vec3(3, 0, 1), true), &e),
            SpawnResult::NameInUse);
  EXPECT_EQ(scene.world().bodyCount(), bodies);
}

TEST(SceneObjects, RemoveLeavesTheOthersUntouched) {
  Scene scene{SceneDef()};
  std::string e;
  SpawnDef a = boxObject("a", Vec3(0.1, 0.1, 0.1), 1.0, Vec3(0, 0, 1.5));
  a.def = test::bundledRagdoll();
  ASSERT_EQ(scene.addRagdoll(a, &e), SpawnResult::Added) << e;
  ASSERT_EQ(scene.addObject(boxObject("crate", Vec3(0.2, 0.2, 0.2), 5, Vec3(3, 0, 1)), &e),
            SpawnResult::Added) << e;
  ASSERT_EQ(scene.addObject(boxObject("shelf", Vec3(0.5, 0.5, 0.05), 1, Vec3(-3, 0, 0.5), true), &e),
            SpawnResult::Added) << e;
  ASSERT_EQ(scene.addObject(boxObject("pot", Vec3(0.1, 0.1, 0.1), 1, Vec3(-3, 0, 1.0)), &e),
            SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  run(scene, 0.3);  // everything in flight
  auto states = [&](const std::vector<std::string>& names) {
    std::vector<BodyState> out;
    for (const std::string& n : names)
      for (BodyId b : scene.bodies(scene.find(n)).bodies) out.push_back(scene.world().bodyState(b));
    return out;
  };
  auto same = [](const std::vector<BodyState>& x, const std::vector<BodyState>& y) {
    if (x.size() != y.size()) return false;
    for (size_t i = 0; i < x.size(); ++i)
      if (x[i].pose.p != y[i].pose.p || x[i].pose.q.coeffs() != y[i].pose.q.coeffs() ||
          x[i].linear_velocity != y[i].linear_velocity ||
          x[i].angular_velocity != y[i].angular_velocity)
        return false;
    return true;
  };
  // The dynamic object.
  std::vector<BodyState> before = states({"a", "pot"});
  const std::vector<BodyId> crate = scene.bodies(scene.find("crate")).bodies;
  ASSERT_TRUE(scene.remove("crate", &e)) << e;
  EXPECT_FALSE(scene.world().isValid(crate[0]));
  EXPECT_EQ(scene.find("crate"), -1);
  EXPECT_TRUE(same(before, states({"a", "pot"})));
  // The static object: the pot on it falls through where it was.
  run(scene, 1.0);
  EXPECT_NEAR(origin(scene, scene.find("pot")).z(), 0.65, 0.01) << "the pot is not on the shelf";
  before = states({"a", "pot"});
  const BodyId shelf = scene.staticObjectBodies(0)[0];
  ASSERT_TRUE(scene.remove("shelf", &e)) << e;
  EXPECT_EQ(scene.staticObjectCount(), 0u);
  EXPECT_FALSE(scene.world().isValid(shelf));
  EXPECT_TRUE(same(before, states({"a", "pot"})));
  run(scene, 1.0);
  EXPECT_NEAR(origin(scene, scene.find("pot")).z(), 0.1, 0.01) << "the pot did not fall";
  // The ragdoll.
  before = states({"pot"});
  ASSERT_TRUE(scene.remove("a", &e)) << e;
  EXPECT_TRUE(same(before, states({"pot"})));
  EXPECT_EQ(scene.ragdollCount(), 1u);
  EXPECT_FALSE(scene.remove("a", &e));
  EXPECT_NE(e.find("no ragdoll or object named"), std::string::npos) << e;
  // Round trip: the names are free again.
  ASSERT_EQ(scene.addObject(boxObject("shelf", Vec3(0.5, 0.5, 0.05), 1, Vec3(3, 3, 0.5), true), &e),
            SpawnResult::Added) << e;
  ASSERT_EQ(scene.addObject(boxObject("crate", Vec3(0.2, 0.2, 0.2), 5, Vec3(3, 0, 1)), &e),
            SpawnResult::Added) << e;
  EXPECT_EQ(scene.staticObjectCount(), 1u);
  EXPECT_EQ(scene.ragdollCount(), 2u);
}

TEST(SceneObjects, ManyStaticObjectsByName) {
  Scene scene{SceneDef()};
  std::string e;
  ASSERT_TRUE(scene.start(&e)) << e;
  for (int i = 0; i < 2000; ++i)
    ASSERT_EQ(scene.addObject(boxObject("s" + std::to_string(i), Vec3(0.1, 0.1, 0.1), 1,
                                        Vec3(i % 50, i / 50, 0.1), true), &e),
              SpawnResult::Added) << e;
  EXPECT_EQ(scene.addObject(boxObject("s1999", Vec3(0.1, 0.1, 0.1), 1, Vec3(0, 0, 5), true), &e),
            SpawnResult::NameInUse);
  for (int i = 0; i < 2000; i += 2) ASSERT_TRUE(scene.remove("s" + std::to_string(i), &e)) << e;
  ASSERT_EQ(scene.staticObjectCount(), 1000u);
  for (size_t i = 0; i < scene.staticObjectCount(); ++i) {
    const std::string& name = scene.staticObjectName(int(i));
    const int n = std::stoi(name.substr(1));
    EXPECT_EQ(n % 2, 1) << name;
    EXPECT_TRUE(scene.staticObjectPose(int(i)).p.isApprox(Vec3(n % 50, n / 50, 0.1), 1e-9)) << name;
    EXPECT_LT((scene.world().bodyPose(scene.staticObjectBodies(int(i))[0]).p -
              Vec3(n % 50, n / 50, 0.1)).norm(), 1e-6) << name;
  }
}

TEST(SceneObjects, ResetPutsObjectsBack) {
  Scene scene{SceneDef()};
  std::string e;
  ASSERT_TRUE(scene.start(&e)) << e;
  ASSERT_EQ(scene.addObject(boxObject("crate", Vec3(0.2, 0.2, 0.2), 5, Vec3(0, 0, 2)), &e),
            SpawnResult::Added) << e;
  ASSERT_EQ(scene.addObject(boxObject("step", Vec3(0.5, 0.5, 0.1), 1, Vec3(3, 0, 0.1), true), &e),
            SpawnResult::Added) << e;
  run(scene, 1.5);
  ASSERT_NEAR(origin(scene, 0).z(), 0.2, 0.01);
  ASSERT_TRUE(scene.reset(&e)) << e;
  const LinkState s = scene.linkState(0, 0);
  EXPECT_EQ(s.pose.p, Vec3(0, 0, 2));
  EXPECT_EQ(s.linear_velocity, Vec3::Zero());
  ASSERT_EQ(scene.staticObjectCount(), 1u);
  const BodyId step = scene.staticObjectBodies(0)[0];
  EXPECT_TRUE(scene.world().isValid(step));
  EXPECT_LT((scene.world().bodyPose(step).p - Vec3(3, 0, 0.1)).norm(), 1e-6);
}

TEST(SceneObjects, BadObjectsAreRefusedWithAMessage) {
  Recorder rec;
  Scene scene(SceneDef(), &rec);
  std::string e;
  ASSERT_TRUE(scene.start(&e)) << e;
  const int bodies = scene.world().bodyCount();
  const Vec3 h(0.1, 0.1, 0.1);
  struct Case {
    SpawnDef spawn;
    SpawnResult result;
    std::string says;
  };
  std::vector<Case> cases;
  SpawnDef s = boxObject("x", h, 1, Vec3(0, 0, 1));
  s.def.links.clear();
  cases.push_back({s, SpawnResult::BadModel, "no links"});
  s = boxObject("x", Vec3(0.1, -0.2, 0.1), 1, Vec3(0, 0, 1));
  cases.push_back({s, SpawnResult::BadModel, "box"});
  s = boxObject("x", Vec3(0.1, NAN, 0.1), 1, Vec3(0, 0, 1), true);
  cases.push_back({s, SpawnResult::BadModel, "box"});
  s = boxObject("x", h, 0.0, Vec3(0, 0, 1));
  cases.push_back({s, SpawnResult::BadModel, "mass"});
  s = boxObject("x", h, NAN, Vec3(0, 0, 1));
  cases.push_back({s, SpawnResult::BadModel, "mass"});
  s = boxObject("x", h, 1, Vec3(0, NAN, 1));
  cases.push_back({s, SpawnResult::WorldRefused, "pose"});
  s = boxObject("x", h, 1, Vec3(0, 0, 1));
  s.pose.q = Quat(NAN, 0, 0, 0);
  cases.push_back({s, SpawnResult::WorldRefused, "orientation"});
  s = boxObject("x", h, 1, Vec3(0, 0, 1));
  s.def.links[0].shapes[0].geometry = Geometry::plane(Vec3::UnitZ(), 0.0);
  cases.push_back({s, SpawnResult::BadModel, "plane"});
  s = boxObject("1x", h, 1, Vec3(0, 0, 1));
  cases.push_back({s, SpawnResult::BadName, "object name"});
  for (const Case& c : cases) {
    e.clear();
    EXPECT_EQ(scene.addObject(c.spawn, &e), c.result) << c.says;
    EXPECT_NE(e.find(c.says), std::string::npos) << e;
    EXPECT_EQ(scene.ragdollCount(), 0u);
    EXPECT_EQ(scene.staticObjectCount(), 0u);
    EXPECT_EQ(scene.world().bodyCount(), bodies);
  }
  run(scene, 0.01);
}

// Item 8: a crate spawned above a ragdoll lying on the ground lands on it and moves it.
TEST(SceneObjects, CrateSpawnedAboveALyingRagdollLandsOnItAndMovesIt) {
  Scene scene{SceneDef()};
  std::string e;
  SpawnDef r;
  r.name = "ragdoll";
  r.def = test::bundledRagdoll();
  // Lying on its back along x.
  r.pose = Transform(Vec3(0, 0, 0.3), Quat(Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitY())));
  ASSERT_EQ(scene.addRagdoll(r, &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  run(scene, 3.0);
  const int k = scene.find("ragdoll");
  const std::vector<BodyId> bodies = scene.bodies(k).bodies;  // a copy: adding moves them
  World& w = scene.world();
  ASSERT_LT(test::maxSpeed(w, bodies), 0.05) << "the ragdoll is not lying still";
  std::vector<Vec3> lying;
  double top = -1e9;
  Vec3 torso = Vec3::Zero();
  for (BodyId b : bodies) lying.push_back(w.bodyState(b).com_position);
  torso = w.bodyState(bodies[size_t(scene.findLink(k, "torso"))]).com_position;
  for (const Vec3& p : lying) top = std::max(top, p.z());
  const Vec3 half(0.2, 0.2, 0.15);
  ASSERT_EQ(scene.addObject(boxObject("crate", half, 20.0, Vec3(torso.x(), torso.y() + 0.15, top + 1.5)),
                            &e),
            SpawnResult::Added) << e;
  const int c = scene.find("crate");
  double hit = 0.0;  // largest ragdoll speed while the crate lands
  for (int i = 0; i < 3000; ++i) {
    scene.step();
    hit = std::max(hit, test::maxSpeed(w, bodies));
  }
  double moved = 0.0;
  for (size_t i = 0; i < bodies.size(); ++i)
    moved = std::max(moved, (w.bodyState(bodies[i]).com_position - lying[i]).norm());
  const Vec3 crate = scene.linkState(c, 0).com;
  RecordProperty("ragdoll_moved_mm", std::to_string(moved * 1e3));
  RecordProperty("ragdoll_hit_speed", std::to_string(hit));
  RecordProperty("crate_z", std::to_string(crate.z()));
  EXPECT_GT(hit, 0.2) << "the crate did not hit the ragdoll";
  EXPECT_GT(moved, 0.005) << "the ragdoll did not move";
  EXPECT_GT(crate.z(), half.z() - 0.005) << "the crate sank into the ground";
  EXPECT_LT(scene.linkState(c, 0).linear_velocity.norm(), 0.05) << "the crate is not at rest";
  const bool on_it = crate.z() > half.z() + 0.05;
  const bool beside = std::hypot(crate.x() - torso.x(), crate.y() - torso.y()) > 0.2;
  EXPECT_TRUE(on_it || beside) << "crate at " << crate.transpose();
}

}  // namespace
