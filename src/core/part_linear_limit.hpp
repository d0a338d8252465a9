// Linear limit part: lower <= s <= upper for the slide position s = a . d of a prismatic joint
// (part_slider_frame.hpp). Two inequality rows with accumulated impulses clamped to >= 0
// (solveInequalityRow, part_rows.hpp) on the LinearRow along the axis a:
//   lower: C = s - lower,  upper: C = upper - s (row negated),
//   m_eff = 1 / (1/mA + 1/mB + (lA x a)^T IA^-1 (lA x a) + (rB x a)^T IB^-1 (rB x a)).
// Position projection (after the substeps): s more than `slop` outside the range is moved back
// to the slop by the position impulse lambda a at the lever arms, lambda = -C' / m_eff^-1 (C'
// the excess beyond the slop, at most max_correction): no velocity is added.
#pragma once

#include <algorithm>

#include "part_rows.hpp"
#include "part_slider_frame.hpp"

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

  static bool project(SolverBody& A, SolverBody& B, const SliderPose& p, double lower,
                      double upper, double slop, double max_correction) {
    const double e =
        std::clamp(rangeExcess(p.position(), lower, upper, slop), -max_correction, max_correction);
    if (e == 0.0) return false;
    const LinearRow row(p.axis, p.leverA(), p.rB, A, B);
    if (!(row.k > 1e-300)) return false;
    applyPairPositionImpulse(A, B, (-e / row.k) * p.axis, p.leverA(), p.rB);
    return true;
  }
};

}  // namespace ragdoll_sim
