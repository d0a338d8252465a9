// rostest: the node reads config/materials.yaml's table and per-link map from the parameter
// server through the conversion loadMaterialFile uses; a bad entry is a FATAL naming it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "node_binary.hpp"
#include "node_log.hpp"

namespace {

int runNode(const std::string& name, const std::string& args, int seconds, std::string* out) {
  return ragdoll_test::runNodeBinary(
      name, std::string("_urdf_file:=") + RAGDOLL_SIM_SOURCE_DIR + "/urdf/ragdoll.urdf " + args,
      seconds, out);
}

}  // namespace

TEST(Materials, ShippedFileLoadsThroughRosparam) {
  const std::string file = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/config/materials.yaml";
  ASSERT_EQ(std::system(("rosparam load " + file + " /materials_ok").c_str()), 0);
  std::string out;
  const int rc = runNode("materials_ok", "", 8, &out);
  EXPECT_EQ(rc, 124) << "the node should run until stopped:\n" << out;
  EXPECT_EQ(out.find("FATAL"), std::string::npos) << out;
  EXPECT_NE(out.find("~link_materials (set)"), std::string::npos) << out;
  std::system("rosparam delete /materials_ok");
}

TEST(Materials, BadEntryIsFatalAndNamed) {
  // Set with rosparam (YAML): `_name:=value` on the command line would give a string.
  struct Case {
    std::string param, yaml;
    std::vector<std::string> words;
  };
  const std::vector<Case> cases = {
      {"link_materials", "{foot_l: rubbr}", {"link_materials/foot_l", "'rubbr'"}},
      {"materials", "{surfaces: {ice: [0.1, 0.03]}}", {"materials/surfaces/ice", "restitution"}},
      {"materials", "{surfaces: {ice: [0.1, 0.03, 0.1]}, pairs: [[ice, rubbr, 0.1, 0.1]]}",
       {"materials/pairs[0]", "'rubbr'"}},
      {"materials", "{surface: {ice: [0.1, 0.03, 0.1]}}", {"unknown key 'surface'"}},
      {"materials", "[1, 2]", {"materials must be a dictionary"}},
  };
  int k = 0;
  for (const Case& c : cases) {
    const std::string name = "materials_bad_" + std::to_string(k++);
    ASSERT_EQ(std::system(("rosparam set /" + name + "/" + c.param + " '" + c.yaml + "'").c_str()), 0);
    std::string out;
    const int rc = runNode(name, "", 60, &out);
    EXPECT_EQ(rc, 1) << c.yaml << ":\n" << out;
    EXPECT_NE(out.find("FATAL"), std::string::npos) << c.yaml << ":\n" << out;
    for (const std::string& w : c.words)
      EXPECT_NE(out.find(w), std::string::npos) << c.yaml << ": " << out;
    std::system(("rosparam delete /" + name).c_str());
  }
}

int main(int argc, char** argv) {
  return ragdoll_test::runRosTests(argc, argv, "materials_test", 1, [] {}, [] {});
}
