// Shared by the world loader's tests: fixture paths and loading with the fixtures' model folder.
#pragma once

#include <gtest/gtest.h>

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

}  // namespace world_test
