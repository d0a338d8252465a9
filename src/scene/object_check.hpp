// What the Scene refuses in an object before it touches the World, each message naming the
// link, the shape and the rule: a model without links, a size or mass that is not a finite
// positive number, a plane on a dynamic link, a pose that is not finite.
#pragma once

#include <string>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {
namespace scene {

// "" or the first problem of `def` for an object (is_static: masses and inertias are unused).
std::string objectModelError(const RagdollDef& def, bool is_static);
// "" or why the World cannot hold a body at `pose` ("pose position must be finite ...").
std::string objectPoseError(const Transform& pose);

// `name` made a valid Scene name (names.hpp): other characters become '_', a leading
// non-letter gets "m_" before it; world files name models freely.
std::string sanitizedName(const std::string& name);

}  // namespace scene
}  // namespace ragdoll_sim
