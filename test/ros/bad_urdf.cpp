// rostest: the node binary, started with ~urdf_file set to each malformed fixture
// (test/urdf/fixtures/bad_*.urdf), exits with code 1 and a FATAL message naming the element.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../urdf/malformed_cases.hpp"
#include "node_log.hpp"

namespace {

// The node with ~urdf_file (`timeout` guards against a node that does not exit; rostest has
// the master in the environment): its exit status and output.
int runNode(const std::string& name, const std::string& urdf, std::string* out) {
  const std::string cmd = "timeout 60 " + std::string(RAGDOLL_SIM_NODE_BIN) + " __name:=" + name +
                          " _urdf_file:=" + urdf;
  return malformed::run(cmd, out);
}

}  // namespace

TEST(BadUrdf, NodeExitsNonZeroNamingTheElement) {
  int k = 0;
  for (const auto& [file, words] : malformed::badCases()) {
    std::string out;
    const int rc = runNode("bad_urdf_node_" + std::to_string(k++), malformed::kFixtures + file, &out);
    EXPECT_EQ(rc, 1) << file << ":\n" << out;
    EXPECT_NE(out.find("FATAL"), std::string::npos) << file << ":\n" << out;
    EXPECT_NE(out.find(file), std::string::npos) << out;
    for (const std::string& w : words) EXPECT_NE(out.find(w), std::string::npos) << file << ": " << out;
  }
}

int main(int argc, char** argv) {
  return ragdoll_test::runRosTests(argc, argv, "bad_urdf_test", 1, [] {}, [] {});
}
