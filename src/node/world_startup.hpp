// ~world_file at start-up: the Gazebo SDF world loaded (loadWorldFile, ~world_strict) into the
// Scene before it starts. Its notes go to INFO (one per kind of thing not simulated), its
// warnings to WARN, a <max_step_size> other than the node's step to one INFO; a failure is an
// error naming the file and the element, which the node turns into one FATAL and exit 1.
#pragma once

#include <string>

#include "node_config.hpp"
#include "ragdoll_sim/scene.hpp"

namespace ragdoll_sim {
namespace node {

// True when there is no ~world_file or it loaded; false with *error otherwise.
bool loadStartupWorld(const NodeConfig& config, Scene* scene, std::string* error);

}  // namespace node
}  // namespace ragdoll_sim
