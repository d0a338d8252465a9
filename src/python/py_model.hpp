// What ragdoll_sim.Model holds: a loaded model, shared by the scenes it is spawned into.
#pragma once

#include <memory>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {
namespace python {

struct PyModel {
  std::shared_ptr<const RagdollDef> def;
};

}  // namespace python
}  // namespace ragdoll_sim
