// A static object of a Scene (a world file's static model, a wall spawned at run time): a
// model whose every link is a static body where it is placed. A world may hold thousands, so
// it is a plain record looked up by name through a hash map, never a RagdollInstance.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {
namespace scene {

struct StaticObject {
  std::string name;
  RagdollDef def;      // its links and their shapes (materials resolved); joints are ignored
  Transform pose;      // root link in the world
  std::vector<BodyId> bodies;  // one per link in the current World (empty before start())
  // Per link, per shape: coefficients the model file wrote itself (surfaces.hpp bits).
  std::vector<std::vector<uint8_t>> written;
  int plane_link = -1;  // a link holding a plane shape (it may replace the default ground)
};

}  // namespace scene
}  // namespace ragdoll_sim
