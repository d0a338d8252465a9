// A material file (config/materials.yaml) read without ROS: the contact material table and the
// per-link material map, as the node reads the same file from ~materials and ~link_materials.
//
//   materials:
//     combine: {friction: geometric_mean, restitution: max}  # geometric_mean | average | min | max
//     surfaces: {name: [mu_s, mu_k, e(, c_r(, hertz(, zeta)))], ...}  # one material against anything
//     pairs:                                                   # measured pairs, either order
//       - [a, b, mu_s, mu_k(, e(, c_r(, hertz(, zeta))))]  # a column left out comes from the two surfaces
//       - [a, [b, c], mu_s, mu_k]          # a list on one side: the row holds for each name
//   link_materials: {link_name: surface, "*": surface}         # "*": every other link
//
// See docs/interface.md for the shipped table and the rules behind its numbers.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "ragdoll_sim/material.hpp"

namespace ragdoll_sim {

struct MaterialFileResult {
  bool ok = false;
  // One message naming the file, the line and the entry, and the rule it breaks
  // ("materials.yaml line 30: materials/pairs[3] names 'rubbr', not in materials/surfaces").
  std::string error;
  MaterialTable table;
  // link name -> surface name (SceneDef::link_materials): exact names in name order, then "*".
  std::vector<std::pair<std::string, std::string>> link_materials;
};

// A regular file of at most kMaxInputFileBytes (urdf_loader.hpp); `materials:` is required,
// `link_materials:` optional, no other top-level keys.
MaterialFileResult loadMaterialFile(const std::string& path);
// The same from text; `name` stands for the file in messages.
MaterialFileResult loadMaterialString(const std::string& yaml, const std::string& name = "materials");

}  // namespace ragdoll_sim
