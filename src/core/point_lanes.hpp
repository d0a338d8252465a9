// The wide pass over the joint anchors (SolverSettings::lanes 4 or 8): the rigid point parts
// (part_point.hpp) of an island range's unbroken ball, hinge and fixed joints are solved in
// float lanes (point_row_wide.hpp) after each joint sweep has solved the joints' other parts.
//
// Per step, the range's joints whose anchor is rigid and unbreakable (no spring, infinite
// break force and torque: no such joint breaks within the step, so the batches stay valid)
// are coloured in joint order (ConstraintGraph, FirstFit; no two of a colour share a dynamic
// body) and packed colour by colour into blocks of kRowBlock lanes; the overflow set past the
// colours stays in its joint's scalar solve (AnchorPart::in_lanes false). The warm start and
// K^-1 stay scalar in double; the blocks take K^-1, the anchors, C and the impulse after each
// warm start, the anchors again after the position update. After each pass the bodies take the
// float changes (WideBodies) and the impulses go back to PointPart::impulse in double, so
// whatever reads them later (forces, breaks, the joint trees, the next warm start) sees them.
//
// Ranges are prepared and solved on different threads: each range keeps its own storage,
// found by its first joint (ranges with joints have distinct first joints).
#pragma once

#include <vector>

#include "constraint_graph.hpp"
#include "island_schedule.hpp"
#include "point_row_wide.hpp"
#include "solver_context.hpp"
#include "wide_bodies.hpp"

namespace ragdoll_sim {

struct Joint;

class PointLanes {
 public:
  // Before the islands are solved (one thread): storage for `joints` active joints.
  void reserve(int joints);

  // After the range's joints are prepared (ctx.lanes != 1): the blocks, and the joints they
  // hold marked in_lanes.
  void build(const IslandRange& p, Joint* const* js, const std::vector<SolverBody>& bodies);
  // After the range's joints warm started: K^-1, anchors, errors and impulses into the blocks.
  void load(const IslandRange& p, Joint* const* js, const std::vector<SolverBody>& bodies);
  // After the range's joints advanced: the refreshed anchors.
  void refreshAnchors(const IslandRange& p, Joint* const* js);
  // One wide pass over the range's blocks, colour by colour.
  void solve(const IslandRange& p, Joint* const* js, std::vector<SolverBody>& bodies,
             const StepContext& ctx, bool use_bias);

 private:
  struct Range {
    ConstraintGraph graph;
    LanePacking packing;
    WideBodies bodies;
    std::vector<GraphEdge> edges;
    std::vector<int> members;  // joint indices of the edges
    std::vector<int> body_index;  // scratch: the members' bodies
    std::vector<int> lane_joint;  // per block lane: joint index, -1 padding
    std::vector<PointRowBlock> blocks;
  };
  Range* rangeOf(const IslandRange& p);

  std::vector<Range> ranges_;  // by the range's first joint
};

}  // namespace ragdoll_sim
