// The node binary run as a child process by a rostest (rostest has the master in the
// environment), for what only its exit status and output show: start-up errors and the
// start-up line.
#pragma once

#include <string>

#include "../urdf/malformed_cases.hpp"

namespace ragdoll_test {

// ragdoll_sim_node as `__name:=name args`, stopped by SIGINT after `seconds` if it has not
// exited (status 124 then; SIGINT lets it shut down and flush its buffered stdout, which
// SIGTERM loses): its exit status and its stdout + stderr.
inline int runNodeBinary(const std::string& name, const std::string& args, int seconds,
                         std::string* out) {
  const std::string cmd = "timeout -s INT " + std::to_string(seconds) + " " +
                          std::string(RAGDOLL_SIM_NODE_BIN) + " __name:=" + name + " " + args;
  return malformed::run(cmd, out);
}

}  // namespace ragdoll_test
