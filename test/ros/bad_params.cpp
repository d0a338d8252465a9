// rostest: the node binary started with one invalid parameter (on the command line, `_name:=`)
// exits with code 1 and a FATAL message naming the parameter; with a valid ~threads or ~lanes it
// runs (until `timeout` stops it) and its start-up line gives the World's thread count and lane
// width; the anatomy parameters show in the ragdoll's start-up lines.
#include <gtest/gtest.h>

#include <cstdlib>
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
      {"_lanes:=2", {"~lanes", "0 (the widest), 1 (double rows), 4 or 8", "got 2"}},
      {"_lanes:=wide", {"lanes", "must be an integer"}},
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
      // Anatomy (config/joints.yaml): the joint or link and the field.
      {"_joints/neck_y/cone:=-0.5", {"joints/neck_y/cone[0]", "(0, pi]", "got -0.5"}},
      {"_joints/neck_y/cone:=wide", {"joints/neck_y/cone", "a list of 2 numbers"}},
      {"_joint_defaults/cone:=0.5", {"joint_defaults", "per ball joint"}},
      {"_link_damping/torso/linear:=-1.0", {"link_damping/torso/linear", ">= 0", "got -1"}},
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

TEST(BadParams, ThreadsAndLanesRunTheNode) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"_threads:=2 _lanes:=1", "substeps on 2 threads (rows in double)"},
      {"_threads:=0", "substeps on all cores (rows in float lanes, "},  // the default lanes
      {"_threads:=1", " wide, from 24 awake bodies)"},                  // ... left to the solver
      {"_lanes:=4", "(rows in float lanes, 4 wide)"}};
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

// A ball's cone and twist and a link's damping from the parameters reach the spawned ragdoll
// (its start-up lines, written as it is spawned).
TEST(BadParams, AnatomyReachesTheRagdoll) {
  // Lists through rosparam (YAML): `_name:=[...]` on the command line would give a string.
  ASSERT_EQ(std::system("rosparam set /anatomy_bad/joints "
                        "'{neck_y: {cone: [0.6, 0.4], twist: [0.5, 0.1]}}'"), 0);
  std::string out;
  EXPECT_EQ(runNode("anatomy_bad", "", 60, &out), 1) << out;
  EXPECT_NE(out.find("joints/neck_y/twist[0] must be <= "), std::string::npos) << out;
  EXPECT_NE(out.find("got 0.5 > 0.1"), std::string::npos) << out;
  ASSERT_EQ(std::system("rosparam set /anatomy_node/joints "
                        "'{neck_y: {cone: [0.6, 0.4], twist: [-0.8, 0.8]}}'"), 0);
  const int rc = runNode("anatomy_node", "_link_damping/hand_l/linear:=2.0", 8, &out);
  EXPECT_EQ(rc, 124) << out;
  EXPECT_NE(out.find("joint 'neck_y+neck_x+neck_z': swing-twist limits, cone 0.6 / 0.4 rad, "
                     "twist -0.8..0.8 rad"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("link 'hand_l': velocity damping linear 2 1/s, angular 0 1/s"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("FATAL"), std::string::npos) << out;
}

int main(int argc, char** argv) {
  return ragdoll_test::runRosTests(argc, argv, "bad_params_test", 1, [] {}, [] {});
}
