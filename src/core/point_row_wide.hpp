// The rigid point part of a joint anchor (part_point.hpp), with a hinge's axis part
// (part_hinge_axis.hpp) and the joint's angle motors and limits (joint_angle_axes.hpp), solved
// for a block of joints at once in float lanes (derivations at the top of point_row_wide.inc).
// Plain records and declarations only: the AVX2 kernel file includes this header too (see
// lanes.hpp for why it must hold no inline code).
#pragma once

#include <cstdint>

#include "lane_bodies.hpp"
#include "normal_row_wide.hpp"

namespace ragdoll_sim {

// A ball joint's three Euler angles.
constexpr int kAngleRows = 3;

// One block of point parts, kRowBlock lanes whatever the width (normal_row_wide.hpp), structure
// of arrays: field[i] belongs to lane i. Symmetric 3x3 matrices are stored as their six entries
// xx, yy, zz, xy, xz, yz. A padding lane has both bodies -1 and all zeros, so its K is 0, its
// K^-1 is 0 and its impulse stays 0. Aligned to a cache line (and a whole number of them, see
// the static_assert): ranges solved by two threads never write the same line.
struct alignas(64) PointRowBlock {
  float r_a[3][kRowBlock], r_b[3][kRowBlock];      // anchors from the COMs (world)
  float k_inv[6][kRowBlock];                       // K^-1 of the substep, formed by warmStartPointRows
  float ii_a[6][kRowBlock], ii_b[6][kRowBlock];    // world inverse inertias, 0 for a static body
  float inv_mass[kRowBlock];                       // 1/mA + 1/mB (0 for a static body's part)
  float error[3][kRowBlock];                       // C at the current position state
  float impulse[3][kRowBlock];                     // accumulated over the substep
  int32_t body_a[kRowBlock], body_b[kRowBlock];    // solver body index, -1: not movable
  // A hinge's axis rows (0 in a lane without one: U = 0, so its K^-1 and impulse stay 0).
  float axis_u1[3][kRowBlock], axis_u2[3][kRowBlock];  // U's columns (world)
  float axis_k_inv[3][kRowBlock];                      // 2x2 K^-1 as xx, yy, xy
  float axis_error[2][kRowBlock];                      // C
  float axis_impulse[2][kRowBlock];                    // accumulated over the substep
  // The joint's angle rows (a ball's three Euler angles, a hinge's one): per angle a motor, then
  // a lower and an upper limit row, all on the same j; a lane's unused rows have j = 0, C open
  // and no motor.
  float angle_j[kAngleRows][3][kRowBlock];         // j (world): theta_dot = j . (wB - wA)
  float angle_ij[kAngleRows][3][kRowBlock];        // (IA^-1 + IB^-1) j, formed by the warm start
  float angle_k_inv[kAngleRows][kRowBlock];        // 1 / (j . (IA^-1 + IB^-1) j), or 0
  float limit_c[kAngleRows][2][kRowBlock];         // theta - lower, upper - theta (open: > 0)
  float limit_impulse[kAngleRows][2][kRowBlock];   // lower, upper: accumulated, >= 0
  // The motor (part_angle_motor.hpp): lambda = -mass_scale (x + bias) / k - impulse_scale acc,
  // clamped to +-max; position target: the motor softness's scales and bias_rate (theta -
  // target); velocity target: 1, 0 and -target_velocity; no drive: all 0.
  float motor_bias[kAngleRows][kRowBlock];
  float motor_mass_scale[kAngleRows][kRowBlock];
  float motor_impulse_scale[kAngleRows][kRowBlock];
  float motor_max[kAngleRows][kRowBlock];          // max_torque h
  float motor_hc[kAngleRows][kRowBlock];           // h c of the viscous damping c (0: none)
  // The damping (solveMotorRow): lambda = -(x h c + mu) / (k h c + 1), mu its impulse over the
  // substep's sweeps; the warm start forms the divisor's inverse and resets mu.
  float motor_damp_scale[kAngleRows][kRowBlock];   // 1 / (k h c + 1)
  float motor_damp_impulse[kAngleRows][kRowBlock];
  float motor_impulse[kAngleRows][kRowBlock];      // the drive's, accumulated
  int32_t angle_rows;                              // rows [0, angle_rows) hold some lane's angle
  int32_t motor_rows;                              // nonzero: some lane has a motor or damping
  int32_t axis_rows;                               // nonzero: some lane holds a hinge
  int32_t colour;                                  // of the constraint graph
};
static_assert(sizeof(PointRowBlock) % 64 == 0, "a block is whole cache lines");

// A sweep's softness (softness.hpp, orRigid): the biased sweep's terms or a rigid row.
struct PointRowParams {
  float bias_rate = 0.0f;
  float mass_scale = 1.0f;
  float impulse_scale = 0.0f;
  float inv_h = 0.0f;  // a limit row inside its range is speculative: bias C / h
  bool use_bias = false;
};

// warmStartPointRows: each block's K^-1 from its anchors (and hinge axes), inverse inertias
// and inverse masses, then its impulses applied to the bodies, blocks [0, count) in order
// (after the substep's anchors and impulses are in the blocks). solvePointRows: one sweep over
// blocks [0, count) in order. At 4 lanes (SSE2) or 8 lanes (AVX2: call it only when
// cpuHasAvx2()); both give the same bits.
namespace kernel_w4 {
void warmStartPointRows(PointRowBlock* blocks, int count, const LaneBodies& bodies);
void solvePointRows(PointRowBlock* blocks, int count, const LaneBodies& bodies,
                    const PointRowParams& params);
}
namespace kernel_w8 {
void warmStartPointRows(PointRowBlock* blocks, int count, const LaneBodies& bodies);
void solvePointRows(PointRowBlock* blocks, int count, const LaneBodies& bodies,
                    const PointRowParams& params);
}
// With AVX-512F (only when cpuHasAvx512()): the 8-lane blocks, two of a colour with the same rows
// at once; the same bits.
namespace kernel_w16 {
void warmStartPointRows(PointRowBlock* blocks, int count, const LaneBodies& bodies);
void solvePointRows(PointRowBlock* blocks, int count, const LaneBodies& bodies,
                    const PointRowParams& params);
}

// The kernels of lane width `width` (chooseLaneWidth's answer: 4 or 8).
void warmStartPointRows(int width, PointRowBlock* blocks, int count, const LaneBodies& bodies);
void solvePointRows(int width, PointRowBlock* blocks, int count, const LaneBodies& bodies,
                    const PointRowParams& params);

}  // namespace ragdoll_sim
