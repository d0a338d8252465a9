// rostest: the node binary, started with ~urdf_file set to each malformed fixture
// (test/urdf/fixtures/bad_*.urdf), exits with code 1 and a FATAL message naming the element.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../urdf/malformed_cases.hpp"
#include "node_binary.hpp"
#include "node_log.hpp"

TEST(BadUrdf, NodeExitsNonZeroNamingTheElement) {
  int k = 0;
  for (const auto& [file, words] : malformed::badCases()) {
    std::string out;
    const std::string args = "_urdf_file:=" + malformed::kFixtures + file;
    const std::string name = "bad_urdf_node_" + std::to_string(k++);
    const int rc = ragdoll_test::runNodeBinary(name, args, 60, &out);
    EXPECT_EQ(rc, 1) << file << ":\n" << out;
    EXPECT_NE(out.find("FATAL"), std::string::npos) << file << ":\n" << out;
    EXPECT_NE(out.find(file), std::string::npos) << out;
    for (const std::string& w : words) EXPECT_NE(out.find(w), std::string::npos) << file << ": " << out;
  }
}

int main(int argc, char** argv) {
  return ragdoll_test::runRosTests(argc, argv, "bad_urdf_test", 1, [] {}, [] {});
}
