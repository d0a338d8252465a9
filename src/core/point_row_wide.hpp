// The rigid point part of a joint anchor (part_point.hpp), solved for a block of joints at once
// in float lanes (the derivation is at the top of point_row_wide.inc).
// Plain records and declarations only: the AVX2 kernel file includes this header too (see
// lanes.hpp for why it must hold no inline code).
#pragma once

#include <cstdint>

#include "lane_bodies.hpp"
#include "normal_row_wide.hpp"

namespace ragdoll_sim {

// One block of point parts, kRowBlock lanes whatever the width (normal_row_wide.hpp), structure
// of arrays: field[i] belongs to lane i. Symmetric 3x3 matrices are stored as their six entries
// xx, yy, zz, xy, xz, yz. A padding lane has both bodies -1 and K^-1 = 0, so its impulse stays 0.
struct alignas(32) PointRowBlock {
  float r_a[3][kRowBlock], r_b[3][kRowBlock];      // anchors from the COMs (world)
  float k_inv[6][kRowBlock];                       // K^-1 of the substep
  float ii_a[6][kRowBlock], ii_b[6][kRowBlock];    // world inverse inertias, 0 for a static body
  float error[3][kRowBlock];                       // C at the current position state
  float impulse[3][kRowBlock];                     // accumulated over the substep
  int32_t body_a[kRowBlock], body_b[kRowBlock];    // solver body index, -1: not movable
};

// A sweep's softness (softness.hpp, orRigid): the biased sweep's terms or a rigid row.
struct PointRowParams {
  float bias_rate = 0.0f;
  float mass_scale = 1.0f;
  float impulse_scale = 0.0f;
  bool use_bias = false;
};

// One sweep over blocks [0, count) in order, at 4 lanes (SSE2) or 8 lanes (AVX2: call it only
// when cpuHasAvx2()). Both give the same bits.
namespace kernel_w4 {
void solvePointRows(PointRowBlock* blocks, int count, const LaneBodies& bodies,
                    const PointRowParams& params);
}
namespace kernel_w8 {
void solvePointRows(PointRowBlock* blocks, int count, const LaneBodies& bodies,
                    const PointRowParams& params);
}

// The kernel of lane width `width` (chooseLaneWidth's answer: 4 or 8).
void solvePointRows(int width, PointRowBlock* blocks, int count, const LaneBodies& bodies,
                    const PointRowParams& params);

}  // namespace ragdoll_sim
