// The malformed URDF fixtures (test/urdf/fixtures/bad_*.urdf) with the words their error must
// name, and a command runner; shared by test_urdf_malformed (loader, ragdoll_check) and the
// rostest bad_urdf (the node).
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

namespace malformed {

const std::string kFixtures = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/test/urdf/fixtures/";

struct BadCase {
  const char* file;
  std::vector<std::string> words;  // the error must name these
};

inline const std::vector<BadCase>& badCases() {
  static const std::vector<BadCase> cases = {
      {"bad_empty.urdf", {"empty"}},
      {"bad_not_xml.urdf", {"not well-formed XML", "line 1"}},
      {"bad_no_robot.urdf", {"<model>", "<robot>"}},
      {"bad_cycle.urdf", {"cycle", "'wrist'"}},
      {"bad_duplicate_link.urdf", {"duplicate link", "'upper_arm'"}},
      {"bad_duplicate_joint.urdf", {"duplicate joint", "'elbow'"}},
      {"bad_missing_parent.urdf", {"joint 'elbow'", "<parent"}},
      {"bad_missing_child.urdf", {"joint 'elbow'", "'ghost'"}},
      {"bad_nan_origin.urdf", {"joint 'elbow'", "<origin>", "nan"}},
      {"bad_negative_radius.urdf", {"link 'upper_arm'", "<collision>", "cylinder radius", "-0.05"}},
      {"bad_negative_box.urdf", {"link 'forearm'", "<collision>", "box half_extents.x", "-0.04"}},
      {"bad_huge_box.urdf", {"link 'upper_arm'", "<collision>", "box half_extents.x", "5e+99"}},
      {"bad_far_origin.urdf", {"joint 'elbow'", "<origin>", "-1e+07", "1048576 m"}},
  };
  return cases;
}

// Runs a shell command, returns its exit status and its stdout + stderr.
inline int run(const std::string& cmd, std::string* out) {
  out->clear();
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return -1;
  std::array<char, 512> buf;
  while (fgets(buf.data(), buf.size(), p)) *out += buf.data();
  const int status = pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace malformed
