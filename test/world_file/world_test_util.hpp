// Shared by the world loader's tests: fixture paths and loading with the fixtures' model folder.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <string>

#include "ragdoll_sim/world_file.hpp"

namespace world_test {

inline std::string fixture(const std::string& name) {
  return std::string(RAGDOLL_SIM_SOURCE_DIR) + "/test/world_file/fixtures/" + name;
}

inline ragdoll_sim::WorldLoadOptions options(bool strict = false) {
  ragdoll_sim::WorldLoadOptions o;
  o.model_paths = {fixture("models")};
  o.strict = strict;
  return o;
}

inline ragdoll_sim::WorldLoadResult load(const std::string& name, bool strict = false) {
  return ragdoll_sim::loadWorldFile(fixture(name), options(strict));
}

inline bool contains(const std::vector<std::string>& lines, const std::string& part) {
  for (const std::string& l : lines)
    if (l.find(part) != std::string::npos) return true;
  return false;
}

inline const ragdoll_sim::WorldModelDef* model(const ragdoll_sim::WorldFileDef& d, const std::string& name) {
  for (const auto& m : d.models)
    if (m.name == name) return &m;
  return nullptr;
}

struct ToolRun {
  int code;
  std::string out;  // stdout and stderr
};

// `ragdoll_check ARGS` with `env` ("NAME=value ...") before it.
inline ToolRun ragdollCheck(const std::string& args, const std::string& env = "") {
  const std::string cmd = env + " " + RAGDOLL_CHECK_BIN + " " + args + " 2>&1";
  ToolRun run{-1, ""};
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return run;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) run.out.append(buf, n);
  const int status = pclose(p);
  run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace world_test
