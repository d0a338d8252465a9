// Malformed URDF files (test/urdf/fixtures/bad_*.urdf, one per case): the loader gives one
// error naming the element, and ragdoll_check exits non-zero with it. (The node's exit is
// checked by the rostest bad_urdf.)
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "malformed_cases.hpp"
#include "ragdoll_sim/urdf_loader.hpp"

using namespace ragdoll_sim;
using malformed::BadCase;
using malformed::badCases;
using malformed::kFixtures;
using malformed::run;

TEST(MalformedUrdf, EveryFixtureIsCovered) {
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(kFixtures))
    files += e.path().filename().string().rfind("bad_", 0) == 0;
  EXPECT_EQ(files, int(badCases().size()));
}

TEST(MalformedUrdf, OneErrorNamingTheElement) {
  for (const BadCase& c : badCases()) {
    const UrdfLoadResult r = loadUrdfFile(kFixtures + c.file);
    ASSERT_FALSE(r.ok) << c.file;
    EXPECT_EQ(r.error.find('\n'), std::string::npos) << r.error;
    EXPECT_EQ(r.error.find("; "), std::string::npos) << "several errors: " << r.error;
    EXPECT_NE(r.error.find(c.file), std::string::npos) << r.error;
    for (const std::string& w : c.words) EXPECT_NE(r.error.find(w), std::string::npos) << c.file << ": " << r.error;
  }
}

TEST(MalformedUrdf, RagdollCheckExitsNonZero) {
  for (const BadCase& c : badCases()) {
    std::string out;
    const int rc = run(std::string(RAGDOLL_CHECK_BIN) + " " + kFixtures + c.file, &out);
    EXPECT_EQ(rc, 1) << c.file << "\n" << out;
    EXPECT_NE(out.find("status=refused"), std::string::npos) << out;
    for (const std::string& w : c.words) EXPECT_NE(out.find(w), std::string::npos) << c.file << ": " << out;
  }
}

TEST(RagdollCheck, ReportsOurRagdollAndExitsZero) {
  std::string out;
  const int rc = run(std::string(RAGDOLL_CHECK_BIN) + " " + RAGDOLL_SIM_SOURCE_DIR +
                         "/urdf/ragdoll.urdf --seconds 1",
                     &out);
  EXPECT_EQ(rc, 0) << out;
  for (const char* w : {"summary: file=ragdoll.urdf status=ok bodies=15 joints=14", "nan=0",
                        "max_penetration_mm=", "max_anchor_error_mm=", "rest_height_m=",
                        "ball ", "hip_l_y+hip_l_x+hip_l_z", "excluded collision pairs (14)"})
    EXPECT_NE(out.find(w), std::string::npos) << w << "\n" << out;
  EXPECT_EQ(run(std::string(RAGDOLL_CHECK_BIN), &out), 2);  // usage
}
