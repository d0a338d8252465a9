// Angle limit part: lower <= theta <= upper for one joint angle whose rate is
//   theta_dot = j . (wB - wA)          (j: world row of the joint's angle Jacobian)
// Two inequality rows with accumulated impulses clamped to >= 0 (solveInequalityRow,
// part_rows.hpp):
//   lower: C = theta - lower,  upper: C = upper - theta (rate -j . (wB - wA)),
//   m_eff = 1 / (j^T (IA^-1 + IB^-1) j).
#pragma once

#include "part_rows.hpp"

namespace ragdoll_sim {

struct AngleLimitPart {
  double lower_impulse = 0.0, upper_impulse = 0.0;

  void warmStart(SolverBody& A, SolverBody& B, const Vec3& j) const {
    // Most limits are open (both impulses 0): skip the two inertia products.
    if (lower_impulse != upper_impulse)
      applyPairAngularImpulse(A, B, (lower_impulse - upper_impulse) * j);
  }

  // k = j^T (IA^-1 + IB^-1) j, computed with the row.
  void solve(SolverBody& A, SolverBody& B, const Vec3& j, double k, double theta, double lower,
             double upper, const StepContext& ctx, bool use_bias) {
    const AngularRow row(j, k);
    solveInequalityRow(A, B, row, theta - lower, lower_impulse, ctx, use_bias);
    solveInequalityRow(A, B, row.negated(), upper - theta, upper_impulse, ctx, use_bias);
  }
};

}  // namespace ragdoll_sim
