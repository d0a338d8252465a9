// Switches that exist only to check an optimisation: internal to the core, its tests and the
// benchmark (the public WorldDef leaves them out; constants.hpp holds their defaults).
#pragma once

#include <cstdint>
#include <string>

#include <utility>
#include <vector>

#include "constants.hpp"
#include "narrowphase.hpp"
#include "ragdoll_sim/world.hpp"

namespace ragdoll_sim {

struct WorldTuning {
  // Pairs of shapes that keep last step's box or plane are carried over instead of found again
  // (collide.hpp). Off: every pair is found every step; the result is the same bit for bit.
  bool carry_sleeping_pairs = true;
  // Shapes of static bodies in their own tree (collide.hpp). Off: they go through the
  // broadphase with the others every step; the pairs and the result are the same bit for bit.
  bool static_tree = true;
  // After the first substep the wide pass keeps the angles it advanced and takes only those the
  // joints recomputed (PointLanes::load). Off: every substep puts them all; the same bits.
  bool lane_angles_kept = true;
  // The joints' exact angles are computed several joints at a time: in the lanes
  // (PointLanes::exactAngles), and with double rows at the first substep (firstSubstepAngles).
  // Off: each joint's warm start computes its own; the same bits.
  bool lane_exact_angles = true;
  // m, manifold_cache.hpp; 0 (or a value not below speculative_distance) turns the cache off.
  double manifold_cache_distance = kManifoldCacheDistance;
  // The threads' ranges of islands in the lanes keep a reserve to steal: -1 while it times
  // faster than none (StealReserve), 0 never, 1 always. The same bits whichever.
  int range_reserve = -1;
  // Last step's island schedule is kept while nothing it is built from changed
  // (World::Impl::scheduleIslands). Off: it is built every step; the same bits.
  bool keep_schedule = true;
};

// "" or what is wrong with the first field ("manifold_cache_distance must be ...").
std::string worldTuningError(const WorldTuning& tuning);

struct WorldInternals {
  static const WorldTuning& tuning(const World& world);
  // Throws std::invalid_argument with worldTuningError's message, changing nothing.
  static void setTuning(World& world, const WorldTuning& tuning);
  // Counters of the static shapes' tree (collide.hpp): how often it was built, and how many
  // static boxes were computed for it; stepping alone changes neither.
  static int64_t staticTreeBuilds(const World& world);
  static int64_t staticBoxesComputed(const World& world);
  // The last collide's pairs (shape ids, a < b), in key order, and every shape's box in it
  // (bounded[s]: an alive shape with a box, not a plane), for comparing with brute force.
  static std::vector<std::pair<int, int>> pairs(const World& world);
  static const std::vector<Aabb>& shapeBoxes(const World& world);
  static std::vector<char> boundedShapes(const World& world);
  // A ball's Euler angles or a hinge's angle as the solver last left them (AngleAxes: the rows
  // it solved, [0, count)), for comparing with the angles at the poses.
  static std::vector<double> solverAngles(const World& world, JointId joint);
  // Contact constraints solved since the world was made, summed over the sweeps (biased and
  // relax) of every substep: each sweep solves each of a step's active contacts once.
  static int64_t contactSweeps(const World& world);
  // How often the island schedule was built (union-find, ranges, split, runs) since the world
  // was made; a step that keeps last step's does not count.
  static int64_t scheduleBuilds(const World& world);
};

}  // namespace ragdoll_sim
