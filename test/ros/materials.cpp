// rostest: the node reads config/materials.yaml's table and per-link map from the parameter
// server through the conversion loadMaterialFile uses; a bad entry is a FATAL naming it.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "node_binary.hpp"

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
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"'_link_materials:={foot_l: rubbr}'", {"link_materials/foot_l", "'rubbr'"}},
      {"'_materials:={surfaces: {ice: [0.1, 0.03]}}'", {"materials/surfaces/ice", "restitution"}},
      {"'_materials:={surfaces: {ice: [0.1, 0.03, 0.1]}, pairs: [[ice, rubbr, 0.1, 0.1]]}'",
       {"materials/pairs[0]", "'rubbr'"}},
      {"'_materials:={surface: {}}'", {"unknown key 'surface'"}},
  };
  int k = 0;
  for (const auto& [args, words] : cases) {
    std::string out;
    const int rc = runNode("materials_bad_" + std::to_string(k++), args, 60, &out);
    EXPECT_EQ(rc, 1) << args << ":\n" << out;
    EXPECT_NE(out.find("FATAL"), std::string::npos) << args << ":\n" << out;
    for (const std::string& w : words)
      EXPECT_NE(out.find(w), std::string::npos) << args << ": " << out;
  }
}
