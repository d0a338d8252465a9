// Material names, colours and fixed bases from SDF: <surface><ragdoll_sim:material>, else the
// link's visual script name as written; modelRagdollDef carries them (with <mu>/<mu2>) onto
// LinkDef, and a joint to the world on the root link pins it.
#include "world_test_util.hpp"

using namespace ragdoll_sim;
using namespace world_test;

namespace {

const char* kWorld = R"(<?xml version="1.0"?>
<sdf version="1.7">
  <world name="materials">
    <model name="crate">
      <pose>0 0 1 0 0 0</pose>
      <link name="body">
        <inertial><mass>2</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
        <collision name="shell">
          <geometry><box><size>0.4 0.4 0.4</size></box></geometry>
          <surface><ragdoll_sim:material> steel </ragdoll_sim:material>
            <friction><ode><mu>0.3</mu><mu2>0.5</mu2></ode></friction></surface>
        </collision>
        <collision name="skid">
          <pose>0 0 -0.25 0 0 0</pose>
          <geometry><box><size>0.4 0.4 0.1</size></box></geometry>
        </collision>
        <visual name="v">
          <geometry><box><size>0.4 0.4 0.4</size></box></geometry>
          <material><script><name>Gazebo/Wood</name></script><diffuse>0.6 0.4 0.2 1</diffuse></material>
        </visual>
      </link>
    </model>
    <model name="crate_2">
      <pose>2 0 1 0 0 0</pose>
      <link name="body">
        <inertial><mass>2</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
        <collision name="shell">
          <geometry><box><size>0.4 0.4 0.4</size></box></geometry>
          <surface><ragdoll_sim:material> steel </ragdoll_sim:material>
            <friction><ode><mu>0.3</mu><mu2>0.5</mu2></ode></friction></surface>
        </collision>
        <collision name="skid">
          <pose>0 0 -0.25 0 0 0</pose>
          <geometry><box><size>0.4 0.4 0.1</size></box></geometry>
        </collision>
        <visual name="v">
          <geometry><box><size>0.4 0.4 0.4</size></box></geometry>
          <material><script><name>Gazebo/Grey</name></script></material>
        </visual>
      </link>
    </model>
    <model name="post">
      <pose>0 3 0 0 0 0</pose>
      <link name="base">
        <inertial><mass>5</mass><inertia><ixx>1</ixx><iyy>1</iyy><izz>1</izz></inertia></inertial>
        <collision name="c"><geometry><cylinder><radius>0.1</radius><length>1</length></cylinder></geometry></collision>
      </link>
      <link name="arm">
        <pose>0 0 0.6 0 0 0</pose>
        <inertial><mass>1</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
        <collision name="c"><geometry><box><size>0.5 0.05 0.05</size></box></geometry></collision>
      </link>
      <joint name="bolt" type="fixed"><parent>world</parent><child>base</child></joint>
      <joint name="swivel" type="revolute"><parent>base</parent><child>arm</child><axis><xyz>0 0 1</xyz></axis></joint>
    </model>
    <model name="door">
      <pose>0 6 0 0 0 0</pose>
      <link name="leaf">
        <inertial><mass>5</mass><inertia><ixx>1</ixx><iyy>1</iyy><izz>1</izz></inertia></inertial>
        <collision name="c"><geometry><box><size>1 0.05 2</size></box></geometry></collision>
      </link>
      <joint name="hinge" type="revolute"><parent>world</parent><child>leaf</child><axis><xyz>0 0 1</xyz></axis></joint>
    </model>
    <model name="lamp">
      <pose>0 9 0 0 0 0</pose>
      <link name="shade">
        <inertial><mass>1</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
        <collision name="c"><geometry><sphere><radius>0.2</radius></sphere></geometry></collision>
      </link>
      <link name="stand">
        <inertial><mass>3</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
        <collision name="c"><geometry><box><size>0.3 0.3 0.1</size></box></geometry></collision>
      </link>
      <joint name="cord" type="ball"><parent>stand</parent><child>shade</child></joint>
      <joint name="screw" type="fixed"><parent>world</parent><child>stand</child></joint>
    </model>
  </world>
</sdf>)";

}  // namespace

TEST(WorldMaterials, SurfaceMaterialElseTheVisualScriptName) {
  const WorldLoadResult r = loadWorldString(kWorld);
  ASSERT_TRUE(r.ok) << r.error;
  const WorldModelDef* crate = model(r.def, "crate");
  const WorldModelDef* crate2 = model(r.def, "crate_2");
  ASSERT_TRUE(crate && crate2);
  const WorldLinkDef& l = crate->links.at(0);
  ASSERT_EQ(l.collisions.size(), 2u);
  EXPECT_EQ(l.collisions[0].material, "steel");
  EXPECT_EQ(l.collisions[1].material, "Gazebo/Wood");
  EXPECT_EQ(l.visual_material, "Gazebo/Wood");
  // The same model with another visual (parsed once, placed twice) keeps its own.
  ASSERT_EQ(crate2->links.at(0).collisions.size(), 2u);
  EXPECT_EQ(crate2->links[0].collisions[0].material, "steel");
  EXPECT_EQ(crate2->links[0].collisions[1].material, "Gazebo/Grey");
  const WorldModelDef* post = model(r.def, "post");
  ASSERT_TRUE(post);
  EXPECT_EQ(post->links.at(0).collisions.at(0).material, "");
}

TEST(WorldMaterials, ModelRagdollDefCarriesMaterialsColoursFriction) {
  const WorldLoadResult r = loadWorldString(kWorld);
  ASSERT_TRUE(r.ok) << r.error;
  const RagdollDef def = modelRagdollDef(*model(r.def, "crate"));
  ASSERT_EQ(def.links.size(), 1u);
  const LinkDef& l = def.links[0];
  EXPECT_EQ(l.material, "Gazebo/Wood");
  const std::vector<std::string> shapes = {"steel", "Gazebo/Wood"};
  EXPECT_EQ(l.shape_materials, shapes);
  ASSERT_EQ(l.shape_friction.size(), 2u);
  EXPECT_DOUBLE_EQ(l.shape_friction[0], 0.4);  // mean of mu 0.3 and mu2 0.5
  EXPECT_LT(l.shape_friction[1], 0.0);         // not given
  EXPECT_TRUE(l.has_color);
  EXPECT_DOUBLE_EQ(l.color[0], 0.6);
  EXPECT_DOUBLE_EQ(l.color[2], 0.2);
  EXPECT_FALSE(def.fixed_base);
  // A link whose collisions all take its visual material names it once.
  const RagdollDef post = modelRagdollDef(*model(r.def, "post"));
  EXPECT_TRUE(post.links[0].shape_materials.empty());
  EXPECT_FALSE(post.links[0].has_color);
}

TEST(WorldMaterials, JointToTheWorldOnTheRootPinsIt) {
  const WorldLoadResult r = loadWorldString(kWorld);
  ASSERT_TRUE(r.ok) << r.error;
  const RagdollDef post = modelRagdollDef(*model(r.def, "post"));
  EXPECT_TRUE(post.fixed_base);
  EXPECT_EQ(post.joints.size(), 1u);  // the swivel; the bolt is the fixed base
  EXPECT_TRUE(contains(post.notes, "joint 'bolt' to the world pins link 'base'"));
  EXPECT_TRUE(post.warnings.empty());
  // A hinge to the world: pinned all the same, and said so.
  const RagdollDef door = modelRagdollDef(*model(r.def, "door"));
  EXPECT_TRUE(door.fixed_base);
  EXPECT_TRUE(contains(door.warnings, "joint 'hinge': a hinge joint to the world holds as a fixed one"));
  // On a link that is not the root: left out, the model stays free, a warning says why.
  const RagdollDef lamp = modelRagdollDef(*model(r.def, "lamp"));
  EXPECT_FALSE(lamp.fixed_base);
  EXPECT_TRUE(contains(lamp.warnings, "joint 'screw' to the world holds link 'stand', not the model's root 'shade'"));
}
