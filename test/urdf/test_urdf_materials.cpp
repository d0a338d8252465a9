// Fixed bases, material names and colours from URDF: a root link "world" fixed-jointed to the
// robot pins the robot's link (Gazebo's convention); <gazebo reference> <ragdoll_sim:material>
// (else Gazebo's <material> script name) names a link's material; <visual><material><color>
// (or a named robot-level material) gives its colour.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "ragdoll_sim/urdf_loader.hpp"

using namespace ragdoll_sim;

namespace {

const char* kInertial = R"(<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>)";

std::string urdfLink(const std::string& name, const std::string& extra = "") {
  return "<link name=\"" + name + "\">" + kInertial +
         "<collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision>" + extra + "</link>";
}

std::string urdfJoint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child, const std::string& origin = "0 0 0") {
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/><origin xyz=\"" + origin + "\"/>" +
         (type == "revolute" ? "<axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>" : "") +
         "</joint>";
}

bool contains(const std::vector<std::string>& lines, const std::string& part) {
  return std::any_of(lines.begin(), lines.end(),
                     [&](const std::string& l) { return l.find(part) != std::string::npos; });
}

const LinkDef* find(const RagdollDef& d, const std::string& name) {
  for (const LinkDef& l : d.links)
    if (l.name == name) return &l;
  return nullptr;
}

}  // namespace

TEST(UrdfFixedBase, WorldLinkFixedToTheRobotPinsItsLink) {
  const std::string xml = "<robot name=\"arm\"><link name=\"world\"/>" + urdfLink("base") + urdfLink("bar") +
                          urdfJoint("bolt", "fixed", "world", "base", "0 0 1") +
                          urdfJoint("hinge", "revolute", "base", "bar") + "</robot>";
  const UrdfLoadResult r = loadUrdfString(xml);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.def.fixed_base);
  ASSERT_EQ(r.def.links.size(), 2u);
  EXPECT_EQ(r.def.links[r.def.root].name, "base");
  EXPECT_EQ(r.def.joints.size(), 1u);
  EXPECT_TRUE(contains(r.def.notes, "link 'world' and fixed joint 'bolt' dropped: 'base' is the root, "
                                    "pinned where it is spawned (a fixed base)"));
  EXPECT_TRUE(contains(r.def.notes, "the joint's <origin> is not applied"));
}

TEST(UrdfFixedBase, OnlyAFixedJointFromALinkNamedWorld) {
  // A massless root of another name is lumped as before: a free robot.
  const UrdfLoadResult other = loadUrdfString("<robot name=\"r\"><link name=\"ground\"/>" + urdfLink("base") +
                                              urdfJoint("bolt", "fixed", "ground", "base") + "</robot>");
  ASSERT_TRUE(other.ok) << other.error;
  EXPECT_FALSE(other.def.fixed_base);
  EXPECT_EQ(other.def.links.at(0).name, "ground");
  // No world link at all.
  const UrdfLoadResult plain = loadUrdfString("<robot name=\"r\">" + urdfLink("base") + "</robot>");
  ASSERT_TRUE(plain.ok) << plain.error;
  EXPECT_FALSE(plain.def.fixed_base);
  // The bundled ragdoll is free.
  const UrdfLoadResult ragdoll = loadUrdfFile(std::string(RAGDOLL_SIM_SOURCE_DIR) + "/urdf/ragdoll.urdf");
  ASSERT_TRUE(ragdoll.ok) << ragdoll.error;
  EXPECT_FALSE(ragdoll.def.fixed_base);
}

TEST(UrdfMaterials, GazeboReferenceNamesTheMaterial) {
  const std::string xml =
      "<robot name=\"r\">" + urdfLink("body") + urdfLink("foot") + urdfLink("sole") + urdfLink("hand") +
      urdfJoint("ankle", "revolute", "body", "foot") + urdfJoint("glue", "fixed", "foot", "sole") +
      urdfJoint("wrist", "revolute", "body", "hand") +
      "<gazebo reference=\"foot\"><mu1>0.7</mu1><material>Gazebo/Black</material></gazebo>"
      "<gazebo reference=\"sole\"><ragdoll_sim:material> rubber </ragdoll_sim:material></gazebo>"
      "<gazebo reference=\"hand\"><ragdoll_sim:material>leather</ragdoll_sim:material></gazebo>"
      "<gazebo reference=\"hand\"><material>Gazebo/Skin</material></gazebo>"
      "</robot>";
  const UrdfLoadResult r = loadUrdfString(xml);
  ASSERT_TRUE(r.ok) << r.error;
  const LinkDef* body = find(r.def, "body");
  const LinkDef* foot = find(r.def, "foot");
  const LinkDef* hand = find(r.def, "hand");
  ASSERT_TRUE(body && foot && hand);
  EXPECT_EQ(body->material, "");
  EXPECT_TRUE(body->shape_materials.empty());
  EXPECT_EQ(hand->material, "leather");  // the named material wins over the script name
  // The foot's own script name; its lumped sole keeps rubber on its shape.
  EXPECT_EQ(foot->material, "Gazebo/Black");
  const std::vector<std::string> shapes = {"Gazebo/Black", "rubber"};
  EXPECT_EQ(foot->shape_materials, shapes);
  ASSERT_EQ(foot->shape_friction.size(), 2u);
  EXPECT_DOUBLE_EQ(foot->shape_friction[0], 0.7);
}

TEST(UrdfMaterials, VisualColourInlineOrNamed) {
  const std::string xml =
      "<robot name=\"r\"><material name=\"orange\"><color rgba=\"1 0.5 0 1\"/></material>" +
      urdfLink("a", "<visual><geometry><box size=\"0.1 0.1 0.1\"/></geometry><material name=\"orange\"/></visual>") +
      urdfLink("b", "<visual><geometry><box size=\"0.1 0.1 0.1\"/></geometry>"
                "<material name=\"blue\"><color rgba=\"0 0 1 0.5\"/></material></visual>") +
      urdfLink("c") + urdfLink("d", "<visual><geometry><box size=\"0.1 0.1 0.1\"/></geometry>"
                            "<material name=\"bad\"><color rgba=\"0 0 2 1\"/></material></visual>") +
      urdfJoint("ab", "revolute", "a", "b") + urdfJoint("ac", "revolute", "a", "c") +
      urdfJoint("ad", "revolute", "a", "d") + "</robot>";
  const UrdfLoadResult r = loadUrdfString(xml);
  ASSERT_TRUE(r.ok) << r.error;
  const LinkDef* a = find(r.def, "a");
  const LinkDef* b = find(r.def, "b");
  const LinkDef* c = find(r.def, "c");
  const LinkDef* d = find(r.def, "d");
  ASSERT_TRUE(a && b && c && d);
  EXPECT_TRUE(a->has_color);
  EXPECT_DOUBLE_EQ(a->color[1], 0.5);
  EXPECT_TRUE(b->has_color);
  EXPECT_DOUBLE_EQ(b->color[2], 1.0);
  EXPECT_DOUBLE_EQ(b->color[3], 0.5);
  EXPECT_FALSE(c->has_color);
  EXPECT_FALSE(d->has_color);  // outside [0, 1]: no colour
}
