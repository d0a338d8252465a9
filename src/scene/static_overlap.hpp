// The rule for a ragdoll placed into static geometry (SceneDef::spawn_overlap): found with
// World::staticOverlap, cleared by a rigid translation of the whole ragdoll.
#pragma once

#include <string>
#include <vector>

#include "ragdoll_sim/world.hpp"

namespace ragdoll_sim {
namespace scene {

// Overlaps up to this deep are left to the contacts, which push them out gently: a body
// resting on the ground sinks a little into it, and its pose read back and set again must not
// count as placed into the ground.
constexpr double kStaticOverlapSlop = 0.005;  // m

struct StaticLift {
  StaticOverlap first;       // the deepest overlap at the pose given (depth 0: none)
  Vec3 lift = Vec3::Zero();  // the translation applied
  bool clear = true;         // false: still overlapping after the passes allowed
};

// Whether `bodies` reach deeper than kStaticOverlapSlop into static shapes (the deepest pair
// in *overlap).
bool overlapsStatics(const World& world, const std::vector<BodyId>& bodies,
                     StaticOverlap* overlap);

// Moves `bodies` rigidly, velocities kept, until their lowest shape point rests on the static
// shapes they reach into: by the deepest overlap's depth along its direction (a plane's
// normal), again while another static shape is still entered, a few passes at most.
StaticLift liftOutOfStatics(World& world, const std::vector<BodyId>& bodies);

}  // namespace scene
}  // namespace ragdoll_sim
