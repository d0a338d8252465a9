// URDF -> RagdollDef (urdfdom). Chains of revolute joints with coincident origins through
// massless links become ball joints; fixed joints are lumped into the parent link.
#pragma once

#include <string>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {

struct UrdfLoadResult {
  bool ok = false;
  std::string error;   // names the offending element when !ok
  RagdollDef def;      // def.notes lists what was approximated
};

UrdfLoadResult loadUrdfString(const std::string& xml);
UrdfLoadResult loadUrdfFile(const std::string& path);

}  // namespace ragdoll_sim
