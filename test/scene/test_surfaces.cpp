// Surfaces by material name (issue 56): a link's or shape's material name, else the Scene's
// per-link map (ragdolls only, "*" = every link), looked up in the material table with its id
// (so pair coefficients apply); "Gazebo/Wood" is "wood" when the table has it; an unknown name
// is one WARN and the default surface; the file's own friction wins; objects default to
// object_surface.
#include <gtest/gtest.h>

#include <string>

#include "object_models.hpp"
#include "ragdoll_sim/scene.hpp"
#include "ragdoll_sim/world_file.hpp"
#include "scene_recorder.hpp"
#include "scene_views.hpp"

using namespace ragdoll_sim;

namespace {

using test::Recorder;

Material surface(double mu, double e = 0.0) { return Material{mu, mu, e, 0.0}; }

SceneDef withTable() {
  SceneDef sd;
  MaterialTable& t = sd.world.materials;
  t.add("rubber", surface(1.0));
  t.add("concrete", surface(0.6));
  t.add("wood", surface(0.4));
  t.setPair(t.find("rubber"), t.find("concrete"), surface(0.9));
  sd.ragdoll_surface = surface(0.7);
  sd.object_surface = surface(0.123);
  return sd;
}

const Material& shapeMaterial(const Scene& scene, BodyId b, int shape = 0) {
  return scene.world().bodyShapes(b).at(size_t(shape)).material;
}

int warnings(const Recorder& rec, const std::string& part) {
  int n = 0;
  for (const SceneMessage& m : rec.messages)
    if (m.level == SceneMessage::Level::Warn && m.text.find(part) != std::string::npos) ++n;
  return n;
}

TEST(SceneSurfaces, RagdollLinksByNameAndMap) {
  SceneDef sd = withTable();
  sd.link_materials = {{"*", "wood"}, {"torso", "rubber"}};
  Recorder rec;
  Scene scene(sd, &rec);
  std::string e;
  SpawnDef a;
  a.name = "a";
  a.def = test::stickModel();
  a.pose.p = Vec3(0, 0, 1);
  SpawnDef b = a;  // the link's own name wins over the map; the shape's over the link's
  b.name = "b";
  b.pose.p = Vec3(0, 3, 1);
  b.def.links[0].material = "concrete";
  b.def.links[1].material = "concrete";
  b.def.links[1].shape_materials = {"Gazebo/Wood"};
  SpawnDef c = a;  // unknown names: the default surface, one WARN each
  c.name = "c";
  c.pose.p = Vec3(0, 6, 1);
  c.def.links[0].material = "rubbr";
  c.def.links[1].material = "Gazebo/Grey";
  for (SpawnDef* s : {&a, &b, &c}) ASSERT_EQ(scene.addRagdoll(*s, &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  const MaterialTable& t = sd.world.materials;
  const std::vector<BodyId> A = scene.bodies(0).bodies, B = scene.bodies(1).bodies,
                            C = scene.bodies(2).bodies;
  EXPECT_EQ(shapeMaterial(scene, A[0]).id, t.find("wood"));
  EXPECT_EQ(shapeMaterial(scene, A[1]).id, t.find("rubber"));
  EXPECT_EQ(shapeMaterial(scene, A[1]).static_friction, 1.0);
  EXPECT_EQ(shapeMaterial(scene, B[0]).id, t.find("concrete"));
  EXPECT_EQ(shapeMaterial(scene, B[1]).id, t.find("wood"));
  EXPECT_EQ(shapeMaterial(scene, C[0]).id, t.find("wood")) << "an unknown name counts as none";
  EXPECT_EQ(warnings(rec, "'rubbr'"), 1);
  EXPECT_NE(warnings(rec, "link 'pelvis'"), 0);
  EXPECT_EQ(shapeMaterial(scene, C[1]).id, t.find("rubber")) << "Gazebo/Grey is no table entry";
  EXPECT_EQ(warnings(rec, "Gazebo/Grey"), 0) << "a Gazebo look is not warned about";
  // The pair entry applies: rubber on concrete resolves to the pair's 0.9.
  EXPECT_EQ(t.resolve(shapeMaterial(scene, A[1]), shapeMaterial(scene, B[0])).static_friction, 0.9);
}

TEST(SceneSurfaces, NoNamesKeepTheRagdollSurface) {
  SceneDef sd = withTable();
  Scene scene(sd);
  std::string e;
  SpawnDef a;
  a.name = "a";
  a.def = test::stickModel();
  a.def.links[1].shape_friction = {0.3};  // URDF mu: wins over any material
  a.def.links[1].material = "rubber";
  a.pose.p = Vec3(0, 0, 1);
  ASSERT_EQ(scene.addRagdoll(a, &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  const Material& pelvis = shapeMaterial(scene, scene.bodies(0).bodies[0]);
  EXPECT_EQ(pelvis.static_friction, 0.7);
  EXPECT_EQ(pelvis.id, 0);
  const Material& torso = shapeMaterial(scene, scene.bodies(0).bodies[1]);
  EXPECT_EQ(torso.static_friction, 0.3);
  EXPECT_EQ(torso.kinetic_friction, 0.3);
  EXPECT_EQ(torso.id, 0);
}

TEST(SceneSurfaces, ObjectsTakeNoLinkMapAndDefaultToObjectSurface) {
  SceneDef sd = withTable();
  sd.link_materials = {{"*", "wood"}};
  Scene scene(sd);
  std::string e;
  ASSERT_TRUE(scene.start(&e)) << e;
  SpawnDef plain = test::boxObject("plain", Vec3(0.1, 0.1, 0.1), 1, Vec3(0, 0, 1));
  SpawnDef named = test::boxObject("named", Vec3(0.1, 0.1, 0.1), 1, Vec3(2, 0, 1), true);
  named.def.links[0].material = "concrete";
  ASSERT_EQ(scene.addObject(plain, &e), SpawnResult::Added) << e;
  ASSERT_EQ(scene.addObject(named, &e), SpawnResult::Added) << e;
  EXPECT_EQ(shapeMaterial(scene, scene.bodies(0).bodies[0]).static_friction, 0.123);
  EXPECT_EQ(shapeMaterial(scene, scene.staticObjectBodies(0)[0]).id,
            sd.world.materials.find("concrete"));
}

TEST(SceneSurfaces, WorldFileSurfaces) {
  const std::string xml =
      "<?xml version='1.0'?><sdf version='1.7'><world name='w'>"
      "<model name='floor'><static>true</static><link name='l'><collision name='c'><geometry>"
      "<plane><normal>0 0 1</normal></plane></geometry></collision>"
      "<visual name='v'><geometry><plane><normal>0 0 1</normal></plane></geometry><material>"
      "<script><uri>file://media/materials/scripts/gazebo.material</uri><name>Gazebo/Wood</name>"
      "</script></material></visual></link></model>"
      "<model name='puck'><pose>0 0 1 0 0 0</pose><link name='l'><collision name='c'><geometry>"
      "<box><size>0.2 0.2 0.2</size></box></geometry><surface><friction><ode><mu>0.2</mu>"
      "<mu2>0.2</mu2></ode></friction><bounce><restitution_coefficient>0.5"
      "</restitution_coefficient></bounce></surface></collision></link></model>"
      "<model name='block'><pose>2 0 1 0 0 0</pose><link name='l'><collision name='c'>"
      "<geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision></link></model>"
      "</world></sdf>";
  const WorldLoadResult w = loadWorldString(xml);
  ASSERT_TRUE(w.ok) << w.error;
  SceneDef sd = withTable();
  Scene scene(sd);
  std::string e;
  ASSERT_TRUE(scene.loadWorld(w.def, &e)) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  EXPECT_EQ(shapeMaterial(scene, scene.ground()).id, sd.world.materials.find("wood"));
  const Material& puck = shapeMaterial(scene, scene.bodies(scene.find("puck")).bodies[0]);
  EXPECT_DOUBLE_EQ(puck.static_friction, 0.2);
  EXPECT_DOUBLE_EQ(puck.restitution, 0.5);
  EXPECT_EQ(shapeMaterial(scene, scene.bodies(scene.find("block")).bodies[0]).static_friction,
            0.123);
}

TEST(SceneSurfaces, SetMaterialsKeepsNamedLinks) {
  SceneDef sd = withTable();
  Scene scene(sd);
  std::string e;
  SpawnDef a;
  a.name = "a";
  a.def = test::stickModel();
  a.def.links[1].material = "rubber";
  a.pose.p = Vec3(0, 0, 1);
  ASSERT_EQ(scene.addRagdoll(a, &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  MaterialTable t2 = sd.world.materials;
  t2.add("rubber", surface(1.1));
  scene.setMaterials(surface(0.55), t2);
  EXPECT_EQ(shapeMaterial(scene, scene.bodies(0).bodies[0]).static_friction, 0.55);
  EXPECT_EQ(shapeMaterial(scene, scene.bodies(0).bodies[1]).static_friction, 1.1);
  EXPECT_EQ(shapeMaterial(scene, scene.ground()).static_friction, 0.55);
  ASSERT_TRUE(scene.reset(&e)) << e;  // and a rebuild keeps them
  EXPECT_EQ(shapeMaterial(scene, scene.bodies(0).bodies[1]).static_friction, 1.1);
}

}  // namespace
