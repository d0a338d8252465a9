// Switches that exist only to check an optimisation: internal to the core, its tests and the
// benchmark (the public WorldDef leaves them out; constants.hpp holds their defaults).
#pragma once

#include <string>

#include "constants.hpp"
#include "ragdoll_sim/world.hpp"

namespace ragdoll_sim {

struct WorldTuning {
  // Pairs of shapes that keep last step's box or plane are carried over instead of found again
  // (collide.hpp). Off: every pair is found every step; the result is the same bit for bit.
  bool carry_sleeping_pairs = true;
  // m, manifold_cache.hpp; 0 (or a value not below speculative_distance) turns the cache off.
  double manifold_cache_distance = kManifoldCacheDistance;
};

// "" or what is wrong with the first field ("manifold_cache_distance must be ...").
std::string worldTuningError(const WorldTuning& tuning);

struct WorldInternals {
  static const WorldTuning& tuning(const World& world);
  // Throws std::invalid_argument with worldTuningError's message, changing nothing.
  static void setTuning(World& world, const WorldTuning& tuning);
};

}  // namespace ragdoll_sim
