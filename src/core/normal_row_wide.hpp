// What the wide kernels share (contact_rows_wide.hpp, point_row_wide.hpp): the block size, and
// the step's constants of the rigid contact normal row. Plain records only: the AVX2 kernel
// files include this header too (see lanes.hpp for why it must hold no inline code).
#pragma once

namespace ragdoll_sim {

// Rows are stored in blocks of this many, whatever the lane width: an 8-wide kernel solves a
// block in one pass, a 4-wide one in two, so the prepared data do not depend on the width
// chosen at run time. The rows of one block share no dynamic body (the colouring's job).
constexpr int kRowBlock = 8;

// The step's constants of the rigid (non-compliant) contact normal row (softness.hpp).
struct NormalRowParams {
  float inv_h = 0.0f;              // 1 / substep
  float bias_rate = 0.0f;          // contact softness
  float mass_scale = 1.0f;
  float impulse_scale = 0.0f;
  float linear_slop = 0.0f;        // m
  float max_push_velocity = 0.0f;  // m/s
  bool use_bias = true;            // false: the relax sweeps (rigid, no push-out)
};

}  // namespace ragdoll_sim
