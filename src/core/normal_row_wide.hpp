// The contact normal row, solved for a block of contact points at once in float lanes (the
// wide solver's building block; the derivation is at the top of normal_row_wide.inc).
// Plain records and declarations only: the AVX2 kernel file includes this header too (see
// lanes.hpp for why it must hold no inline code).
#pragma once

#include <cstdint>

namespace ragdoll_sim {

// Rows are stored in blocks of this many, whatever the lane width: an 8-wide kernel solves a
// block in one pass, a 4-wide one in two, so the prepared data do not depend on the width
// chosen at run time. The rows of one block share no dynamic body (the colouring's job).
constexpr int kRowBlock = 8;

// One block of normal rows, structure of arrays: field[i] belongs to row (lane) i. A padding
// lane has both bodies static (-1) and mass 0, so its impulse stays 0.
struct alignas(32) NormalRowBlock {
  float n[3][kRowBlock];                          // contact normal, from A to B
  float ang_a[3][kRowBlock], ang_b[3][kRowBlock];    // rA x n, rB x n
  float iang_a[3][kRowBlock], iang_b[3][kRowBlock];  // IA^-1 (rA x n), IB^-1 (rB x n)
  float inv_mass_a[kRowBlock], inv_mass_b[kRowBlock];  // 0 for a static body
  float mass[kRowBlock];         // 1 / (J M^-1 J^T)
  float separation[kRowBlock];   // at the current position state (> 0: apart)
  float impulse[kRowBlock];      // accumulated normal impulse of the substep (>= 0)
  float max_impulse[kRowBlock];  // largest single increment (restitution's trigger)
  int32_t body_a[kRowBlock], body_b[kRowBlock];  // into BodyVelocitiesF, -1: static
};

// Body velocities in float, structure of arrays: v[k][b] is component k of body b's linear
// velocity, w[k][b] of its angular velocity.
struct BodyVelocitiesF {
  float* v[3];
  float* w[3];
};

// The same velocities as one record of 8 floats per body (Box2D v3's layout): a lane reads
// its body with one 32-byte load (two 16-byte ones at 4 lanes) and a transpose turns W records
// into fields. pad is written as 0.
struct alignas(32) BodyVelocityF {
  float v[3], w[3], pad[2];
};

// The step's constants of the rigid (non-compliant) contact row (softness.hpp).
struct NormalRowParams {
  float inv_h = 0.0f;              // 1 / substep
  float bias_rate = 0.0f;          // contact softness
  float mass_scale = 1.0f;
  float impulse_scale = 0.0f;
  float linear_slop = 0.0f;        // m
  float max_push_velocity = 0.0f;  // m/s
  bool use_bias = true;            // false: the relax sweeps (rigid, no push-out)
};

// One sweep over blocks [0, count) in order, at 4 lanes (SSE2) or 8 lanes (AVX2: call it only
// when cpuHasAvx2()). Both give the same bits.
// solveNormalRowsAos: the same with the bodies as records; the same bits.
namespace kernel_w4 {
void solveNormalRows(NormalRowBlock* blocks, int count, const BodyVelocitiesF& bodies,
                     const NormalRowParams& params);
void solveNormalRowsAos(NormalRowBlock* blocks, int count, BodyVelocityF* bodies,
                        const NormalRowParams& params);
}
namespace kernel_w8 {
void solveNormalRows(NormalRowBlock* blocks, int count, const BodyVelocitiesF& bodies,
                     const NormalRowParams& params);
void solveNormalRowsAos(NormalRowBlock* blocks, int count, BodyVelocityF* bodies,
                        const NormalRowParams& params);
}

// The kernel of lane width `width` (chooseLaneWidth's answer: 4 or 8).
void solveNormalRows(int width, NormalRowBlock* blocks, int count, const BodyVelocitiesF& bodies,
                     const NormalRowParams& params);
void solveNormalRowsAos(int width, NormalRowBlock* blocks, int count, BodyVelocityF* bodies,
                        const NormalRowParams& params);

}  // namespace ragdoll_sim
