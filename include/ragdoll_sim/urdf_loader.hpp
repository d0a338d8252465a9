// URDF -> RagdollDef (urdfdom, with a tinyxml2 pre-pass for malformed files and extensions).
// Chains of revolute joints with coincident origins through massless links become ball joints;
// fixed joints are lumped into the parent link; meshes become convex hulls when the file
// resolves, else a primitive fitted to the visual geometry or the inertia. See docs/urdf.md
// for what maps to what.
#pragma once

#include <string>
#include <vector>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {

struct UrdfLoadOptions {
  std::string base_dir;                    // relative mesh paths (loadUrdfFile: the file's folder)
  std::vector<std::string> package_paths;  // package:// lookup; empty: $ROS_PACKAGE_PATH
  bool load_meshes = true;                 // false: every mesh gets the fallback primitive
};

struct UrdfLoadResult {
  bool ok = false;
  std::string error;   // one message naming the offending element when !ok
  RagdollDef def;      // def.notes: what was merged; def.warnings: what was approximated / repaired
};

UrdfLoadResult loadUrdfString(const std::string& xml, const UrdfLoadOptions& options = {});
UrdfLoadResult loadUrdfFile(const std::string& path, UrdfLoadOptions options = {});

}  // namespace ragdoll_sim
