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
// warm start, the anchors again after the position update. The kernel reads and writes the
// double solver bodies itself (the impulse reaches v through the double inverse masses).
// After the substep's last joint sweep the impulses go back to PointPart::impulse in double,
// so whatever reads them later (forces, breaks, the joint trees, the next warm start) sees them.
//
// Ranges are prepared and solved on different threads: each range keeps its own storage,
// found by its first joint (ranges with joints have distinct first joints). A range whose
// joints and bodies are those of the last step at its slot keeps its colouring.
#pragma once

#include <vector>

#include "constraint_graph.hpp"
#include "island_schedule.hpp"
#include "point_row_wide.hpp"
#include "solver_context.hpp"

namespace ragdoll_sim {

struct Joint;
struct AnchorPart;

class PointLanes {
 public:
  // Before the islands are solved (one thread): storage for `joints` active joints.
  void reserve(int joints);

  // After the range's joints are prepared (ctx.lanes != 1): the blocks, and the joints they
  // hold marked in_lanes.
  void build(const IslandRange& p, Joint* const* js, const std::vector<SolverBody>& bodies);
  // After the range's joints warm started: K^-1, errors and impulses into the blocks, and the
  // anchors when the warm start refreshed them (anchors_moved: the first substep; later ones
  // keep what refreshAnchors put after the last position update).
  void load(const IslandRange& p, const std::vector<SolverBody>& bodies, bool anchors_moved);
  // After the range's joints advanced: the refreshed anchors.
  void refreshAnchors(const IslandRange& p);
  // One wide pass over the range's blocks, colour by colour; sync: the impulses back to the
  // joints (the substep's last joint sweep).
  void solve(const IslandRange& p, std::vector<SolverBody>& bodies, const StepContext& ctx,
             bool use_bias, bool sync);

 private:
  // A used lane: its joint's anchor and bodies (block l / kRowBlock, lane l % kRowBlock).
  struct Lane {
    AnchorPart* anchor;
    int a, b;
    int slot;  // l
  };
  struct Range {
    std::vector<Lane> lanes;
    std::vector<PointRowBlock> blocks;
    // What the layout was coloured from: a step with the same anchors on the same bodies keeps it.
    std::vector<AnchorPart*> anchors;
    std::vector<GraphEdge> edges;
  };
  Range* rangeOf(const IslandRange& p);

  std::vector<Range> ranges_;  // by the range's first joint
};

}  // namespace ragdoll_sim
