// What ragdoll_sim.Model and ragdoll_sim.WorldFile hold: a file loaded once, shared by the scenes
// it goes into.
#pragma once

#include <memory>

#include "ragdoll_sim/ragdoll.hpp"
#include "ragdoll_sim/world_file.hpp"

namespace ragdoll_sim {
namespace python {

struct PyModel {
  std::shared_ptr<const RagdollDef> def;
};

struct PyWorldFile {
  std::shared_ptr<const WorldFileDef> def;
};

// An SDF world file read by the world loader; std::runtime_error naming the file and the element.
PyWorldFile loadWorldFileOrThrow(const std::string& path, bool strict);

}  // namespace python
}  // namespace ragdoll_sim
