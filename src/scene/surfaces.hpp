// Which surface each shape of a model gets: the first material the table knows of the names
// given per shape, per link and by the Scene's per-link map, with its id so that its pair
// coefficients apply; else the Scene's default surface for the model's kind. Coefficients the
// model file wrote itself (URDF mu, SDF <surface>) win over both.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "ragdoll_sim/material.hpp"
#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {
namespace scene {

// Bits of a shape's `written` flags: its ShapeDef::material holds the file's own friction
// (static = kinetic) or restitution.
constexpr uint8_t kWrittenFriction = 1;
constexpr uint8_t kWrittenRestitution = 2;

struct SurfaceRules {
  const MaterialTable* table = nullptr;
  // Link name -> material name ("*" = every link); nullptr for objects.
  const std::vector<std::pair<std::string, std::string>>* link_materials = nullptr;
  Material fallback;        // a shape that names no known material
  Material plane_fallback;  // ... when it is a plane (a world's ground)
};

// The material table's id of `name`, or -1: "Gazebo/Wood" stands for "wood" when the table has
// that. *unknown is set when the name should be warned about (not a "Gazebo/..." name).
int findMaterial(const MaterialTable& table, const std::string& name, bool* unknown);

// Sets every shape's material of *def by the rules; `written` (per link, per shape, may be
// shorter) keeps the file's coefficients. Returns one warning per link and unknown name.
std::vector<std::string> resolveSurfaces(RagdollDef* def, const SurfaceRules& rules,
                                         const std::vector<std::vector<uint8_t>>& written);

}  // namespace scene
}  // namespace ragdoll_sim
