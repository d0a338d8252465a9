// rostest: the node binary, started with ~urdf_file set to each malformed fixture
// (test/urdf/fixtures/bad_*.urdf), exits with code 1 and a FATAL message naming the element.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "node_log.hpp"

namespace {

const std::string kFixtures = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/test/urdf/fixtures/";

// Runs the node (a `timeout` guards against a node that does not exit; rostest has the master
// and ROS_MASTER_URI in the environment), returns its exit status and its output.
int runNode(const std::string& name, const std::string& urdf, std::string* out) {
  const std::string cmd = "timeout 60 " + std::string(RAGDOLL_SIM_NODE_BIN) + " __name:=" + name +
                          " _urdf_file:=" + urdf + " 2>&1";
  out->clear();
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return -1;
  std::array<char, 512> buf;
  while (fgets(buf.data(), buf.size(), p)) *out += buf.data();
  const int status = pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST(BadUrdf, NodeExitsNonZeroNamingTheElement) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"bad_empty.urdf", {"empty"}},
      {"bad_not_xml.urdf", {"not well-formed XML"}},
      {"bad_no_robot.urdf", {"<model>", "<robot>"}},
      {"bad_cycle.urdf", {"cycle", "'wrist'"}},
      {"bad_duplicate_link.urdf", {"duplicate link", "'upper_arm'"}},
      {"bad_duplicate_joint.urdf", {"duplicate joint", "'elbow'"}},
      {"bad_missing_parent.urdf", {"joint 'elbow'", "<parent"}},
      {"bad_missing_child.urdf", {"joint 'elbow'", "'ghost'"}},
      {"bad_nan_origin.urdf", {"joint 'elbow'", "nan"}},
  };
  int k = 0;
  for (const auto& [file, words] : cases) {
    std::string out;
    const int rc = runNode("bad_urdf_node_" + std::to_string(k++), kFixtures + file, &out);
    EXPECT_EQ(rc, 1) << file << ":\n" << out;
    EXPECT_NE(out.find("FATAL"), std::string::npos) << file << ":\n" << out;
    EXPECT_NE(out.find(file), std::string::npos) << out;
    for (const std::string& w : words) EXPECT_NE(out.find(w), std::string::npos) << file << ": " << out;
  }
}

int main(int argc, char** argv) {
  return ragdoll_test::runRosTests(argc, argv, "bad_urdf_test", 1, [] {}, [] {});
}
