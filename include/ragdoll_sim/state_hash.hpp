// The determinism hash: FNV-1a over the bits of every body's pose and velocities. Two runs
// that agree bit for bit agree on it; bench_ragdoll folds it over every step (--opt hash=1),
// the Python Scene reads it of the current state.
#pragma once

#include <cstdint>

#include "ragdoll_sim/world.hpp"

namespace ragdoll_sim {

constexpr uint64_t kFnvOffsetBasis = 14695981039346656037ull;

// Folds every body's position, orientation (w x y z) and linear and angular velocity, in body
// id order, into h (removed bodies' slots skipped).
uint64_t hashStates(const World& world, uint64_t h = kFnvOffsetBasis);

}  // namespace ragdoll_sim
