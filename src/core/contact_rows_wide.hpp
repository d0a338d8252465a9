// Contact manifolds solved in float lanes, one manifold per lane (the wide solver's contact
// rows; the derivation is at the top of contact_rows_wide.inc). Plain records and declarations
// only: the AVX2 kernel file includes this header too (see lanes.hpp for why).
#pragma once

#include <cstdint>

#include "lane_bodies.hpp"
#include "normal_row_wide.hpp"

namespace ragdoll_sim {

// The most points of a manifold (Manifold::kMaxPoints, checked in contact_wide.cpp).
constexpr int kBlockPoints = 4;

// One Jacobian row of every lane of a block: angX = rX x d, iangX = IX^-1 angX, 1 / (J M^-1 J^T).
struct alignas(32) ContactRowLanes {
  float ang_a[3][kRowBlock], ang_b[3][kRowBlock];
  float iang_a[3][kRowBlock], iang_b[3][kRowBlock];
  float mass[kRowBlock];
};

// One point of every lane: its normal and two tangent rows, its state in the substeps.
struct alignas(32) ContactPointLanes {
  ContactRowLanes row[3];        // normal, tangent 0, tangent 1
  float separation[kRowBlock];   // at the current position state (> 0: apart)
  float impulse[3][kRowBlock];   // accumulated: normal (>= 0), tangent 0, tangent 1
  float max_impulse[kRowBlock];  // largest single normal increment (restitution's trigger)
};

// kRowBlock manifolds that share no dynamic body, structure of arrays: field[i] is lane i's.
// A padding lane or point has mass 0 and zero rows, so it takes no impulse and moves nothing.
struct alignas(32) ContactBlock {
  float n[3][kRowBlock], t0[3][kRowBlock], t1[3][kRowBlock];  // normal (A to B), tangents
  float friction[kRowBlock];
  float inv_mass_a[kRowBlock], inv_mass_b[kRowBlock];  // 0 for a static body
  int32_t body_a[kRowBlock], body_b[kRowBlock];        // solver body, -1: not movable
  int32_t points;                                      // the most points of a lane
  int32_t colour;                                      // of the constraint graph
  ContactPointLanes point[kBlockPoints];
};

// One sweep over blocks [0, count) in order: the warm start (the accumulated impulses applied),
// or the solve (normal rows, then friction), reading and writing the double solver bodies.
// Width 4 (SSE2) or 8 (AVX2: only when cpuHasAvx2()); both give the same bits.
namespace kernel_w4 {
void warmStartContactBlocks(ContactBlock* blocks, int count, const LaneBodies& bodies);
void solveContactBlocks(ContactBlock* blocks, int count, const LaneBodies& bodies,
                        const NormalRowParams& params);
}
namespace kernel_w8 {
void warmStartContactBlocks(ContactBlock* blocks, int count, const LaneBodies& bodies);
void solveContactBlocks(ContactBlock* blocks, int count, const LaneBodies& bodies,
                        const NormalRowParams& params);
}
// With AVX-512F (only when cpuHasAvx512()): the 8-lane blocks, two of a colour at once.
namespace kernel_w16 {
void warmStartContactBlocks(ContactBlock* blocks, int count, const LaneBodies& bodies);
void solveContactBlocks(ContactBlock* blocks, int count, const LaneBodies& bodies,
                        const NormalRowParams& params);
}

}  // namespace ragdoll_sim
