// Malformed worlds: one message naming the element, from the loader and from
// `ragdoll_check --world` (exit 1).
#include <algorithm>
#include <fstream>

#include "world_test_util.hpp"

using namespace ragdoll_sim;
using namespace world_test;

namespace {

struct Case {
  const char* name;
  std::string xml;
  const char* expected;  // part of the error
};

std::string world(const std::string& body, const char* version = "1.7") {
  return std::string("<?xml version=\"1.0\"?><sdf version=\"") + version + "\"><world name=\"w\">" + body +
         "</world></sdf>";
}

std::string boxModel(const std::string& size, const std::string& pose = "0 0 0 0 0 0") {
  return "<model name=\"m\"><static>1</static><pose>" + pose +
         "</pose><link name=\"l\"><collision name=\"c\"><geometry><box><size>" + size +
         "</size></box></geometry></collision></link></model>";
}

const std::vector<Case>& cases() {
  static const std::vector<Case> c = {
      {"empty", "", "the world file is empty"},
      {"not_xml", "<sdf version='1.7'><world name='w'>", "not well-formed XML"},
      {"not_sdf", "<robot name='r'/>", "root element is <robot>, expected <sdf>"},
      {"no_world", "<sdf version='1.7'><model name='m'><link name='l'/></model></sdf>", "holds no <world>"},
      {"negative_size", world(boxModel("1 -2 1")),
       "model 'm' link 'l' collision 'c' <box><size>: must be finite and > 0, got 1 -2 1"},
      {"negative_radius",
       world("<model name='m'><static>1</static><link name='l'><collision name='c'><geometry><cylinder>"
             "<radius>-0.1</radius><length>1</length></cylinder></geometry></collision></link></model>"),
       "collision 'c' <cylinder><radius> <length>: must be finite and > 0, got -0.1 1"},
      {"nan_pose", world(boxModel("1 1 1", "0 nan 0 0 0 0")),
       "world 'w' model 'm' <pose>: '0 nan 0 0 0 0' is not 6 finite numbers"},
      {"nan_pose_over_lines", world(boxModel("1 1 1", "0\n  nan 0\n\t0 0 0")),
       "world 'w' model 'm' <pose>: '0 nan 0 0 0 0' is not 6 finite numbers"},
      {"nan_gravity", world("<gravity>0 0 inf</gravity>"), "world 'w' <gravity>: '0 0 inf'"},
      {"unknown_geometry",
       world("<model name='m'><link name='l'><collision name='c'><geometry><cone><radius>1</radius></cone>"
             "</geometry></collision></link></model>"),
       "model 'm' link 'l' collision 'c' <geometry> <cone>: unknown geometry <cone>"},
      {"no_geometry", world("<model name='m'><link name='l'><collision name='c'/></link></model>"),
       "model 'm' link 'l' collision 'c': no <geometry> shape"},
      {"joint_to_nowhere",
       world("<model name='m'><link name='l'/><joint name='j' type='revolute'><parent>l</parent>"
             "<child>ghost</child><axis><xyz>0 0 1</xyz></axis></joint></model>"),
       "SDF: "},
      {"zero_mass",
       world("<model name='m'><link name='l'><inertial><mass>0</mass></inertial></link></model>"),
       "model 'm' link 'l' <inertial><mass>: must be a finite number > 0"},
      {"bad_friction",
       world("<model name='m'><static>1</static><link name='l'><collision name='c'><geometry><sphere>"
             "<radius>1</radius></sphere></geometry><surface><friction><ode><mu>-1</mu></ode></friction>"
             "</surface></collision></link></model>"),
       "SDF: model 'm' link 'l' collision 'c' <surface> <friction> <ode> <mu>: "},
      {"zero_plane_normal",
       world("<model name='m'><static>1</static><link name='l'><collision name='c'><geometry><plane>"
             "<normal>0 0 0</normal></plane></geometry></collision></link></model>"),
       "collision 'c' <plane><normal>: must be a finite non-zero vector"},
      // SDFormat 12 throws from its 1.7 -> 1.8 conversion of a joint named like a nested path
      {"joint_name_with_delimiter",
       world("<model name='m'><link name='a'/><link name='b'/><joint name='x::y' type='fixed'>"
             "<parent>a</parent><child>b</child></joint></model>"),
       "SDF: SDFormat 12 refused the document: Joint's <parent> value does not start with x"},
      {"missing_include_strict", world("<include><uri>model://nowhere</uri></include>"),
       "<include> world 'w' <include> model://nowhere: model 'nowhere' not found"},
  };
  return c;
}

}  // namespace

TEST(WorldMalformed, EachGivesOneMessageNamingTheElement) {
  for (const Case& c : cases()) {
    const WorldLoadResult r = loadWorldString(c.xml, options(true));
    EXPECT_FALSE(r.ok) << c.name;
    EXPECT_NE(r.error.find(c.expected), std::string::npos) << c.name << ": " << r.error;
    EXPECT_EQ(r.error.find('\n'), std::string::npos) << c.name << ": " << r.error;
    EXPECT_TRUE(r.def.models.empty()) << c.name;
  }
}

TEST(WorldMalformed, MissingIncludeWithoutStrictIsAWarning) {
  const WorldLoadResult r = loadWorldString(world("<include><uri>model://nowhere</uri></include>"), options());
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.def.counts.unresolved, 1);
  EXPECT_TRUE(contains(r.def.warnings, "model://nowhere: model 'nowhere' not found"));
}

TEST(WorldMalformed, NotARegularFile) {
  const WorldLoadResult r = loadWorldFile("/dev/zero");
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("world file '/dev/zero' is not a regular file"), std::string::npos) << r.error;
}

TEST(WorldCheckTool, RefusalsExitOneWithTheMessage) {
  const std::string dir = ::testing::TempDir();
  for (const Case& c : cases()) {
    const std::string path = dir + "/malformed_" + c.name + ".world";
    std::ofstream(path) << c.xml;
    const ToolRun r = ragdollCheck("--world " + path + " --strict");
    EXPECT_EQ(r.code, 1) << c.name << ": " << r.out;
    EXPECT_NE(r.out.find(c.expected), std::string::npos) << c.name << ": " << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << c.name << ": " << r.out;
  }
  const ToolRun cycle = ragdollCheck("--world " + fixture("cycle.world"), "GAZEBO_MODEL_PATH=" + fixture("models"));
  EXPECT_EQ(cycle.code, 1);
  EXPECT_NE(cycle.out.find("a cycle of includes"), std::string::npos) << cycle.out;
}

TEST(WorldCheckTool, SummaryLineFirst) {
  const ToolRun r = ragdollCheck("--world " + fixture("duplicates.world"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(r.out.rfind("world=duplicates status=ok models=4 static_shapes=4 dynamic_bodies=0 skipped=0 "
                        "unresolved=0\nnotes (0):\nwarnings (2):\n", 0),
            0u)
      << r.out;
}
