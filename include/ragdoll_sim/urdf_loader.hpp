// URDF -> RagdollDef (urdfdom, with a tinyxml2 pre-pass for malformed files and extensions).
// Chains of revolute joints with coincident origins through massless links become ball joints;
// fixed joints are lumped into the parent link; meshes become convex hulls when the file
// resolves, else a primitive fitted to the visual geometry or the inertia. See docs/urdf.md
// for what maps to what.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {

// The largest URDF, package.xml or mesh file the loader reads. Only regular files are read: a
// device, pipe, directory or larger file is refused before anything is read.
constexpr std::size_t kMaxInputFileBytes = std::size_t(64) << 20;  // 64 MiB

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

// <gazebo reference="LINK"><dampingFactor>d</dampingFactor>: Gazebo classic (ODE) multiplies
// the link's linear and angular velocity by (1 - d) after every physics step, 1 ms by default.
// The loader sets LinkDef linear_damping = angular_damping = this rate (1/s), the same decay
// per second as Gazebo at its default step (ODE's small-speed threshold is not modelled).
constexpr double kGazeboDefaultStep = 0.001;  // s
inline double dampingFactorRate(double d) { return -std::log1p(-d) / kGazeboDefaultStep; }

UrdfLoadResult loadUrdfString(const std::string& xml, const UrdfLoadOptions& options = {});
// `text`, when given, receives the file's contents as read (the file is read once).
UrdfLoadResult loadUrdfFile(const std::string& path, UrdfLoadOptions options = {},
                            std::string* text = nullptr);

}  // namespace ragdoll_sim
