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
// inverse inertias and inverse masses go into the blocks once per step, the anchors, their
// error C and the hinge axes' U and C once per position state (the first substep's warm start,
// then after each position update), formed in double lanes from the step-start frames
// (point_frames.hpp) with the bits of the parts' own refresh, and copied back to the parts
// (the joint trees, the limit projection and the reports read them there; the parts leave the
// refresh to the lanes). Each substep the blocks take the impulses (and the angles' rows,
// errors, motor terms and impulses; the angles computed in double where the joint's warm
// start would, several joints at once: exactAngles),
// and the kernel forms K^-1 from the anchors (and axes) and applies the warm start, colour by
// colour, in place of the joints' scalar ones.
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
#include "joint_angles_lanes.hpp"
#include "point_frames.hpp"
#include "point_row_wide.hpp"
#include "solver_context.hpp"

namespace ragdoll_sim {

struct Joint;
struct AnchorPart;
struct HingeAxisPart;
template <int N>
struct AngleAxes;

class PointLanes {
 public:
  // Before the islands are solved (one thread): storage for `joints` active joints.
  void reserve(int joints);

  // After the range's joints are prepared (ctx.lanes != 1): the blocks, and the joints they
  // hold marked in_lanes.
  void build(const IslandRange& p, Joint* const* js, const std::vector<SolverBody>& bodies);
  // Of the range built last at p: the joints in the blocks to rows, the blocks' lanes to lanes.
  void addLaneFill(const IslandRange& p, int& rows, int& lanes) const;
  // Before the range's joints warm start: the exact angles and rows of the joints whose angle
  // rows are all in the lanes (hinges, Euler ball joints) where their warm start would compute
  // them (AngleAxes::recomputes), W joints at a time (joint_angles_lanes.hpp), with the bits of
  // their own updateAngle; the first substep marks them (AngleAxes::exact_in_lanes), so that
  // their warm start leaves it out.
  void exactAngles(const IslandRange& p, std::vector<SolverBody>& bodies, const StepContext& ctx,
                   bool first_substep);
  // After the range's joints warm started: the impulses into the blocks, and the anchors and
  // errors at the step's first position state (anchors_moved: the first substep; later ones
  // keep what refreshAnchors formed after the last position update); then K^-1 and the warm
  // start in lanes. The angle rows go in at the first substep (all_angles); later ones keep
  // the angles the lanes advanced and the impulses they solved (synced to the parts at each
  // substep's last sweep), and take only the angles the joints recomputed (AngleAxes::fresh).
  void load(const IslandRange& p, std::vector<SolverBody>& bodies, const StepContext& ctx,
            bool anchors_moved, bool all_angles);
  // After the range's joints advanced: the anchors and errors at the new position state, and
  // what moves with the advanced angles (limit errors, position motors' bias).
  void refreshAnchors(const IslandRange& p, std::vector<SolverBody>& bodies,
                      const StepContext& ctx);
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
    bool exact;      // its angles are computed in the lanes (exactAngles' jobs)
  };
  // The exact-angle jobs of a range's lanes whose angle rows are all there (exactAngles): formed
  // at a first substep and kept while the lanes, the lanes that have jobs and the body arrays
  // (the jobs point into them) stay as they were.
  struct AngleJobs {
    template <int N>
    struct Of {  // a job's joint axes and bodies
      AngleAxes<N>* axes;
      int a, b;
    };
    std::vector<HingeAngleJob> hinges;
    std::vector<EulerAngleJob> balls;
    std::vector<Of<1>> hinge_of;
    std::vector<Of<3>> ball_of;
    std::vector<double> ok;  // a ball's rows formed (not at gimbal lock)
    bool valid = false;
    const SolverBody* bodies = nullptr;
    const BodyMotion* motions = nullptr;
  };
  struct alignas(64) Range {  // its own cache lines (allocated by the thread that builds it)
    std::vector<Lane> lanes;
    std::vector<PointRowBlock> blocks;
    std::vector<PointFrameBlock> frames;  // block k's anchors and axes in double
    // What the layout was coloured from: a step with the same anchors on the same bodies keeps it.
    std::vector<AnchorPart*> anchors;
    std::vector<GraphEdge> edges;
    AngleJobs angle_jobs;
  };
  Range* rangeOf(const IslandRange& p) const;
  // The anchors and axes at the bodies' current deltas into the blocks, and back to the parts;
  // with advance_angles, the angles advanced by h too (refreshPointFrames).
  static void refreshFrames(Range& R, std::vector<SolverBody>& bodies, bool advance_angles,
                            double h);

  std::vector<std::unique_ptr<Range>> ranges_;  // by the range's first joint, null until built
};

}  // namespace ragdoll_sim
