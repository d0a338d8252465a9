// Per-link velocity damping of the node's ragdolls (SceneDef::link_damping, ~link_damping in
// config/joints.yaml), resolved onto a RagdollDef before it is spawned. ROS-free.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "ragdoll_sim/ragdoll.hpp"
#include "ragdoll_sim/scene.hpp"

namespace ragdoll_sim {
namespace scene {

// "" when the fields present are finite and >= 0, else a message starting with `where`.
std::string validateLinkDamping(const LinkDamping& d, const std::string& where);

// Sets the links' linear / angular damping: "*" first, then the named entries over it; a field
// an entry leaves out keeps the link's value (the URDF's dampingFactor). Returns a warning per
// name that matches no link (ignored).
std::vector<std::string> applyLinkDamping(
    RagdollDef* def, const std::vector<std::pair<std::string, LinkDamping>>& entries);

}  // namespace scene
}  // namespace ragdoll_sim
