// The one conversion of a material file's entries into a MaterialTable and a per-link map,
// shared by loadMaterialFile and the node (which hands its ~materials / ~link_materials
// parameters over as YAML nodes), so that both give the same table and the same messages.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <utility>
#include <vector>

#include "ragdoll_sim/material.hpp"

namespace ragdoll_sim {
namespace material_yaml {

// `materials` ({combine, surfaces, pairs}; null: nothing) into *table. `where` names it
// ("parameter /sim/materials", "materials.yaml: materials"); *error names the entry and rule.
bool readTable(const YAML::Node& materials, const std::string& where, MaterialTable* table,
               std::string* error);

// `map` ({link name: surface}; null: nothing) into *out, exact names sorted then "*"; every
// surface must be one of `table`'s.
bool readLinkMaterials(const YAML::Node& map, const std::string& where, const MaterialTable& table,
                       std::vector<std::pair<std::string, std::string>>* out, std::string* error);

}  // namespace material_yaml
}  // namespace ragdoll_sim
