// Tuning constants of the core: private, like Box2D's constants.h. The result of a step does not
// depend on any of them; they decide only how the work is spread and what is skipped.
#pragma once

namespace ragdoll_sim {

// Below this many pairs / awake bodies a step is too short to gain from waking other threads:
// the fork-join costs more than the work it would share.
constexpr int kParallelMin = 48;

// An island with at least this many awake bodies, and more than half the awake work (bodies,
// joints, contacts), is split in two (island_split.hpp). A smaller share needs no split: the
// runs of whole islands already balance the threads, and a split island takes every other
// island along in lockstep with its halves. The test depends only on the islands, not on the
// thread count, so the result stays the same for every count.
constexpr int kSplitMin = 60;

// m: a touching pair keeps its manifold (carried along with the shapes) instead of running the
// narrowphase while no point of one shape has moved more than this relative to the other since
// the manifold was computed, and both bodies move less than (speculative_distance - this) per
// step (manifold_cache.hpp). Separated pairs are kept regardless (exact).
constexpr double kManifoldCacheDistance = 0.001;

}  // namespace ragdoll_sim
