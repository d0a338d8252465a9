// The wide pass over the joint anchors (SolverSettings::lanes 4 or 8): the rigid point parts
// (part_point.hpp) of an island range's unbroken ball, hinge and fixed joints are solved in
// float lanes (point_row_wide.hpp) after each joint sweep has solved the joints' other parts;
// a hinge's axis part (part_hinge_axis.hpp) and the angle motors and limits of a ball or hinge
// (joint_angle_axes.hpp) go into the anchor's lane and solve first there: the angles, the
// axis, the anchor, as the scalar joint orders them.
//
// Per step, the range's joints whose anchor is rigid and unbreakable (no spring, infinite
// break force and torque: no such joint breaks within the step, so the batches stay valid)
// are coloured in joint order (ConstraintGraph, FirstFit; no two of a colour share a dynamic
// body) and packed colour by colour into blocks of kRowBlock lanes; the overflow set past the
// colours stays in its joint's scalar solve (AnchorPart::in_lanes false). The bodies' world
// inverse inertias and inverse masses go into the blocks once per step, the anchors and the
// hinge axes' U and C (formed in double, HingeAxisPart::refresh) once per position state (the
// first substep's warm start, then after each position update). Each substep the blocks take
// C and the impulses (and the angles' rows, errors, motor terms and impulses, the angles
// computed in double by the joint's warm start), and the kernel forms K^-1 from the anchors
// (and axes) and applies the warm start, colour by colour, in place of the joints' scalar ones.
// The kernels read and write the double solver bodies themselves (the impulse reaches v
// through the double inverse masses). After the substep's last joint sweep the impulses go
// back to PointPart::impulse, HingeAxisPart::impulse and the angle parts in double, so whatever
// reads them later (forces, breaks, the joint trees, which add to them, the next warm start)
// sees them.
//
// Ranges are prepared and solved on different threads: each range keeps its own storage, found
// by its first joint (ranges with joints have distinct first joints) and allocated by the thread
// that first builds it; its blocks are whole cache lines, so two threads never write one line.
// A range whose joints and bodies are those of the last step at its slot keeps its colouring.
#pragma once

#include <memory>
#include <vector>

#include "constraint_graph.hpp"
#include "island_schedule.hpp"
#include "point_row_wide.hpp"
#include "solver_context.hpp"

namespace ragdoll_sim {

struct Joint;
struct AnchorPart;
struct HingeAxisPart;

class PointLanes {
 public:
  // Before the islands are solved (one thread): storage for `joints` active joints.
  void reserve(int joints);

  // After the range's joints are prepared (ctx.lanes != 1): the blocks, and the joints they
  // hold marked in_lanes.
  void build(const IslandRange& p, Joint* const* js, const std::vector<SolverBody>& bodies);
  // After the range's joints warm started: errors and impulses into the blocks, and the anchors
  // when the warm start refreshed them (anchors_moved: the first substep; later ones keep what
  // refreshAnchors put after the last position update); then K^-1 and the warm start in lanes.
  void load(const IslandRange& p, std::vector<SolverBody>& bodies, const StepContext& ctx,
            bool anchors_moved);
  // After the range's joints advanced: the refreshed anchors and what moves with the advanced
  // angles (limit errors, position motors' bias).
  void refreshAnchors(const IslandRange& p, const StepContext& ctx);
  // One wide pass over the range's blocks, colour by colour; sync: the impulses back to the
  // joints (the substep's last joint sweep).
  void solve(const IslandRange& p, std::vector<SolverBody>& bodies, const StepContext& ctx,
             bool use_bias, bool sync);

 private:
  // A used lane: its joint's anchor (and hinge axis, or null) and bodies, and where it sits.
  struct Lane {
    Joint* joint;
    AnchorPart* anchor;
    HingeAxisPart* axis;
    int a, b;
    int block, lane;
    int angle_rows;  // the joint's angle rows in the lane this step (0: none)
  };
  struct alignas(64) Range {  // its own cache lines (allocated by the thread that builds it)
    std::vector<Lane> lanes;
    std::vector<PointRowBlock> blocks;
    // What the layout was coloured from: a step with the same anchors on the same bodies keeps it.
    std::vector<AnchorPart*> anchors;
    std::vector<GraphEdge> edges;
  };
  Range* rangeOf(const IslandRange& p) const;

  std::vector<std::unique_ptr<Range>> ranges_;  // by the range's first joint, null until built
};

}  // namespace ragdoll_sim
