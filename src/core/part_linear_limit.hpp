// Linear limit part: lower <= s <= upper for the slide position s = a . d of a prismatic joint
// (part_slider_frame.hpp). Two inequality rows with accumulated impulses clamped to >= 0
// (solveInequalityRow, part_rows.hpp) on the LinearRow along the axis a:
//   lower: C = s - lower,  upper: C = upper - s (row negated),
//   m_eff = 1 / (1/mA + 1/mB + (lA x a)^T IA^-1 (lA x a) + (rB x a)^T IB^-1 (rB x a)).
#pragma once

#include "part_rows.hpp"

namespace ragdoll_sim {

struct LinearLimitPart {
  double lower_impulse = 0.0, upper_impulse = 0.0;

  void warmStart(SolverBody& A, SolverBody& B, const LinearRow& row) const {
    row.apply(A, B, lower_impulse - upper_impulse);
  }

  void solve(SolverBody& A, SolverBody& B, const LinearRow& row, double s, double lower,
             double upper, const StepContext& ctx, bool use_bias) {
    solveInequalityRow(A, B, row, s - lower, lower_impulse, ctx, use_bias);
    solveInequalityRow(A, B, row.negated(), upper - s, upper_impulse, ctx, use_bias);
  }
};

}  // namespace ragdoll_sim
