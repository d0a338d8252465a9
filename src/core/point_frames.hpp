// The anchors and hinge axes of a block of joints (PointRowBlock's lanes) at the bodies' current
// rotation and displacement deltas, and the joints' angles advanced with the positions, in
// double lanes, once per position state: what PointPart::refresh and PointPart::error
// (part_point.hpp), HingeAxisPart::refresh (part_hinge_axis.hpp) and AngleAxes::advance with
// the limits' errors (joint_angle_axes.hpp, point_lanes.cpp) compute one joint at a time, with
// the same bits (point_frames_kernel.hpp), so the wide pass (point_lanes.hpp) and the joints'
// scalar parts see the same numbers.
// Plain records and declarations only: the AVX2 kernel file includes this header too.
#pragma once

#include <cstdint>

#include "lane_bodies.hpp"
#include "point_row_wide.hpp"

namespace ragdoll_sim {

// A limit error (rad) past which the row is open for good; the cap keeps C / h finite in float.
constexpr double kFarOpen = 1e6;

// Lane i of a PointRowBlock's frames, structure of arrays in double; whole cache lines.
struct alignas(64) PointFrameBlock {
  // At the start of the step (the parts' prepare), world: zero in a lane without the part.
  double r_a0[3][kRowBlock], r_b0[3][kRowBlock];  // anchors from the COMs
  double center[3][kRowBlock];                    // xB - xA with the carries (centerOffset)
  double a1[3][kRowBlock], b2[3][kRowBlock], c2[3][kRowBlock];  // a hinge's axes
  // The angle rows [0, angle_rows) of the row block: each row's limit (limited 1: on, 0: the
  // row is open) for the step; its world rate row j and angle as the joint's warm start left
  // them (PointLanes::load), the angle advanced by refreshPointFrames.
  double lower[kAngleRows][kRowBlock], upper[kAngleRows][kRowBlock];
  double limited[kAngleRows][kRowBlock];
  double angle_j[kAngleRows][3][kRowBlock];
  double angles[kAngleRows][kRowBlock];
  // At the current deltas (refreshPointFrames).
  double r_a[3][kRowBlock], r_b[3][kRowBlock];
  double u1[3][kRowBlock], u2[3][kRowBlock], axis_c[2][kRowBlock];  // a hinge's U and C
  // The lane's solver bodies, static ones included (a padding lane: any body, all parts zero).
  int32_t body_a[kRowBlock], body_b[kRowBlock];
};
static_assert(sizeof(PointFrameBlock) % 64 == 0, "a block is whole cache lines");

// Blocks [0, count): each frame's double results, and into its row block the anchors r_a, r_b,
// the error and (where the row block holds a hinge) the axis rows and errors in float; with
// advance_angles, the angles advance by h (j . (wB - wA)) and the row block takes the limits'
// errors. Padding lanes get zeros where they share a group of W lanes with used ones; the
// groups past the last used lane are skipped.
void refreshPointFrames(PointFrameBlock* frames, PointRowBlock* rows, int count,
                        const LaneBodies& bodies, bool advance_angles, double h);

// The kernels behind it, four lanes in AVX registers (point_frames_w4.cpp: only on a CPU with
// AVX2) and two in SSE2 ones (point_frames.cpp).
namespace point_frames_w4 {
void refresh(PointFrameBlock* frames, PointRowBlock* rows, int count, const LaneBodies& bodies,
             bool advance_angles, double h);
}
namespace point_frames_w2 {
void refresh(PointFrameBlock* frames, PointRowBlock* rows, int count, const LaneBodies& bodies,
             bool advance_angles, double h);
}

}  // namespace ragdoll_sim
