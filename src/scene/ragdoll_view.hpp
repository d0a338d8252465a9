// One simulated ragdoll as the display and interaction components see it: read-only pointers
// into the node's model and world handles. The node builds the list; the components never own it.
#pragma once

#include <string>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {
namespace scene {

struct RagdollView {
  std::string name;          // unique per node: marker namespace, interactive marker name
  std::string tf_prefix;     // prepended to link names in TF ("" = none); markers and picks
                             // work in the world frame and do not need it
  const RagdollDef* def = nullptr;
  const Ragdoll* ragdoll = nullptr;
};

}  // namespace scene
}  // namespace ragdoll_sim
