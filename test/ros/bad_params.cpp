// rostest: the node binary started with one invalid parameter (on the command line, `_name:=`)
// exits with code 1 and a FATAL message naming the parameter; with a valid ~threads it runs
// (until `timeout` stops it) and its start-up line gives the World's thread count.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "node_binary.hpp"
#include "node_log.hpp"

namespace {

// The bundled ragdoll, and the parameter under test.
int runNode(const std::string& name, const std::string& args, int seconds, std::string* out) {
  return ragdoll_test::runNodeBinary(
      name, std::string("_urdf_file:=") + RAGDOLL_SIM_SOURCE_DIR + "/urdf/ragdoll.urdf " + args,
      seconds, out);
}

}  // namespace

TEST(BadParams, NodeExitsNonZeroNamingTheParameter) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"_threads:=-1", {"~threads", "got -1"}},
      {"_threads:=100000", {"~threads", "got 100000"}},
      {"_threads:=two", {"threads", "must be an integer"}},
      {"_substeps:=0", {"~substeps", "got 0"}},
      {"_physics_rate:=-5.0", {"~physics_rate", "got -5"}},
      {"_gravity:=[0.0,-9.81]", {"gravity", "list of 3 numbers"}},
      {"_sleep/speed:=-0.5", {"~sleep/speed", "got -0.5"}},
      {"_sleep/rest_substeps:=-2", {"~sleep/rest_substeps", "got -2"}},
      // Checked by the core's worldDefError / materialError, named as the node's parameters.
      {"_position_iterations:=-1", {"~position_iterations", "got -1"}},
      {"_max_angular_speed:=0.0", {"~max_angular_speed", "> 0", "got 0"}},
      {"_restitution:=1.5", {"~restitution", "[0, 1]", "got 1.5"}},
      {"_sleep/rest_time:=-0.25", {"~sleep/rest_time", "got -0.25"}},
      // The ranges of dynamic_reconfigure (cfg/Physics.cfg) hold at start-up too.
      {"_real_time_factor:=0.001", {"~real_time_factor", "0 (as fast as possible) or [0.01, 1000]",
                                    "got 0.001"}},
      {"_real_time_factor:=5000.0", {"~real_time_factor", "got 5000"}},
      {"_real_time_factor:=-1.0", {"~real_time_factor", "got -1"}},
      {"_substeps:=100", {"~substeps", "[1, 64]", "got 100"}},
      {"_physics_rate:=10.0", {"~physics_rate", "[1e-05, 0.05]", "got 10"}},
      {"_sleep/speed:=20.0", {"~sleep/speed", "[0, 10]", "got 20"}},
      {"_static_friction:=20.0", {"~static_friction", "[0, 10]", "got 20"}},
      {"_sleep/time:=100.0", {"~sleep/time", "[0, 60]", "got 100"}},
      // The reports' rates and thresholds.
      {"_contacts/rate:=-1.0", {"~contacts/rate", "got -1"}},
      {"_impacts/min_impulse:=-2.0", {"~impacts/min_impulse", "got -2"}},
      {"_injury/fall_speed:=0.01", {"~injury/fall_speed", "~injury/rest_speed"}},
  };
  int k = 0;
  for (const auto& [args, words] : cases) {
    std::string out;
    const int rc = runNode("bad_params_node_" + std::to_string(k++), args, 60, &out);
    EXPECT_EQ(rc, 1) << args << ":\n" << out;
    EXPECT_NE(out.find("FATAL"), std::string::npos) << args << ":\n" << out;
    for (const std::string& w : words)
      EXPECT_NE(out.find(w), std::string::npos) << args << ": " << out;
  }
}

TEST(BadParams, ThreadsRunTheNode) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"_threads:=2", "substeps on 2 threads"}, {"_threads:=0", "substeps on all cores"}};
  int k = 0;
  for (const auto& [args, words] : cases) {
    std::string out;
    // 124: still running when `timeout` stopped it after 8 s.
    const int rc = runNode("threads_node_" + std::to_string(k++), args, 8, &out);
    EXPECT_EQ(rc, 124) << args << ":\n" << out;
    EXPECT_NE(out.find(words), std::string::npos) << args << ":\n" << out;
    EXPECT_EQ(out.find("FATAL"), std::string::npos) << args << ":\n" << out;
  }
}

int main(int argc, char** argv) {
  return ragdoll_test::runRosTests(argc, argv, "bad_params_test", 1, [] {}, [] {});
}
