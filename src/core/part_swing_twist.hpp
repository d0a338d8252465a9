// Swing-twist limit part of a ball joint (angles and rows: joint_angles.hpp, swingTwist):
//   cone:  C = cone - swing >= 0,  row -s (s: unit swing rotation axis, swing_dot = s . (wB - wA)),
//          m_eff = 1 / (s^T (IA^-1 + IB^-1) s);
//   twist: lower <= twist <= upper on the row (tA + tB) / (1 + tA . tB) (an AngleLimitPart).
// Inequality rows with accumulated impulses clamped to >= 0 (solveInequalityRow,
// part_rows.hpp): speculative while inside the limit, soft when pushing out, rigid in relax.
// The angles and rows are computed at the current substep poses by update() (at warm start,
// reused by the biased solve, again before the relax pass). A row that is undefined (swing = 0
// for the cone, which is then inactive for cone > 0; swing = pi for the twist) is skipped.
// Position projection: as AngleLimitPart::project, the cone being the range [-inf, cone].
#pragma once

#include <limits>

#include "joint_angles.hpp"
#include "part_angle_limit.hpp"

namespace ragdoll_sim {

struct SwingTwistPart {
  SwingTwist angles;  // at the current substep poses
  double cone_impulse = 0.0;
  AngleLimitPart twist;

  void update(const Quat& frame_a, const Quat& frame_b, const Vec3& axis) {
    angles = swingTwist(frame_a, frame_b, axis);
    if (!angles.swing_valid) cone_impulse = 0.0;
    if (!angles.twist_valid) twist = AngleLimitPart();
  }

  void warmStart(SolverBody& A, SolverBody& B) const {
    if (angles.swing_valid) applyPairAngularImpulse(A, B, -cone_impulse * angles.swing_row);
    if (angles.twist_valid) twist.warmStart(A, B, angles.twist_row);
  }

  void solve(SolverBody& A, SolverBody& B, double cone, double twist_lower, double twist_upper,
             const StepContext& ctx, bool use_bias) {
    if (angles.twist_valid)
      twist.solve(A, B, angles.twist_row, AngularRow(angles.twist_row, A, B).k, angles.twist,
                  twist_lower, twist_upper, ctx, use_bias);
    if (angles.swing_valid)
      solveInequalityRow(A, B, AngularRow(-angles.swing_row, A, B), cone - angles.swing,
                         cone_impulse, ctx, use_bias);
  }

  // After update() at the current poses.
  bool project(SolverBody& A, SolverBody& B, double cone, double twist_lower, double twist_upper,
               double slop, double max_correction) const {
    bool moved = false;
    if (angles.twist_valid)
      moved = AngleLimitPart::project(A, B, angles.twist_row, AngularRow(angles.twist_row, A, B).k,
                                      angles.twist, twist_lower, twist_upper, slop, max_correction);
    if (angles.swing_valid)
      moved |= AngleLimitPart::project(A, B, angles.swing_row, AngularRow(angles.swing_row, A, B).k,
                                       angles.swing, -std::numeric_limits<double>::infinity(), cone,
                                       slop, max_correction);
    return moved;
  }
};

}  // namespace ragdoll_sim
