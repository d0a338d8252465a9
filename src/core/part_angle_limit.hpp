// Angle limit part: lower <= theta <= upper for one joint angle whose rate is
//   theta_dot = j . (wB - wA)          (j: world row of the joint's angle Jacobian)
// Two inequality rows with accumulated impulses clamped to >= 0 (solveInequalityRow,
// part_rows.hpp):
//   lower: C = theta - lower,  upper: C = upper - theta (rate -j . (wB - wA)),
//   m_eff = 1 / (j^T (IA^-1 + IB^-1) j).
// Position projection (after the substeps, SolverSettings::position_iterations): an angle more than
// `slop` outside its range is turned back to `slop` outside by the angular position impulse
// L = lambda j, lambda = -C' / k (C' the excess beyond the slop, at most max_correction): A
// turns by -IA^-1 L and B by IB^-1 L, so theta moves by k lambda = -C' to first order, and no
// velocity is added. The projection exists because a limb pinned between the ground and a
// heavy falling body is driven past its limit faster than the soft rows bring it back. The slop
// is left to the soft rows, so a limb resting on its limit is not moved every step.
#pragma once

#include <algorithm>

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
    // Both rows open with nothing accumulated: each would take solveInequalityRow's speculative
    // exit (the upper row's rate is exactly -rate), so one rate decides for the two.
    if (lower_impulse == 0.0 && upper_impulse == 0.0) {
      const double travel = ctx.h * j.dot(B.w - A.w);
      const double cl = theta - lower, cu = upper - theta;
      if (cl > 0.0 && cu > 0.0 && cl + travel >= 0.0 && cu - travel >= 0.0) return;
    }
    const AngularRow row(j, k);
    solveInequalityRow(A, B, row, theta - lower, lower_impulse, ctx, use_bias);
    solveInequalityRow(A, B, row.negated(), upper - theta, upper_impulse, ctx, use_bias);
  }

  // True when it turned the bodies (as every project() of the parts).
  static bool project(SolverBody& A, SolverBody& B, const Vec3& j, double k, double theta,
                      double lower, double upper, double slop, double max_correction) {
    if (!(k > 1e-300)) return false;
    const double e =
        std::clamp(rangeExcess(theta, lower, upper, slop), -max_correction, max_correction);
    if (e == 0.0) return false;
    applyPairAngularPositionImpulse(A, B, (-e / k) * j);
    return true;
  }
};

}  // namespace ragdoll_sim
