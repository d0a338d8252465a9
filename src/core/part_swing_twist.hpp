// Swing-twist limit part of a ball joint (angles and rows: joint_angles.hpp, swingTwist):
//   cone:  C = R(s) - swing >= 0 on the row J (dC/dt = J . (wB - wA)), m_eff = 1 / (J^T (IA^-1 +
//          IB^-1) J); circular cone: R = cone, J = -s (s: unit swing rotation axis); elliptical
//          (SwingCone::elliptic): R(s) = a b / sqrt(b^2 (s.u)^2 + a^2 (s.v)^2) with u, v the
//          swing axes carried by frame A, and J adds R's rate as s turns about t (swingConeRow);
//   twist: lower <= twist <= upper on the row (tA + tB) / (1 + tA . tB) (an AngleLimitPart).
// Inequality rows with accumulated impulses clamped to >= 0 (solveInequalityRow,
// part_rows.hpp): speculative while inside the limit, soft when pushing out, rigid in relax.
// The angles and rows are computed at the current substep poses by update() (at warm start,
// reused by the biased solve, again before the relax pass). A row that is undefined (swing = 0
// for the cone, which is then inactive for cone > 0; swing = pi for the twist) is skipped.
// Position projection: as AngleLimitPart::project on the row -J, the cone being [-inf, R].
#pragma once

#include <cmath>
#include <limits>

#include "joint_angles.hpp"
#include "part_angle_limit.hpp"

namespace ragdoll_sim {

// The cone of a ball joint's swing: half-angle a about u, b about v (joint frame, unit, both
// perpendicular to the twist axis); a circular cone when !elliptic (b unused).
struct SwingCone {
  double a = 0.0, b = 0.0;
  bool elliptic = false;
  Vec3 u = Vec3::UnitY(), v = Vec3::UnitZ();
};

// Bound R and the row J of C = R - swing for an elliptical cone; frame A's u, v and t in world axes.
inline void swingConeRow(const SwingCone& cone, const SwingTwist& st, const Vec3& uA,
                         const Vec3& vA, const Vec3& tA, const Vec3& tB, double* bound, Vec3* row) {
  const Vec3& s = st.swing_row;
  const double c = s.dot(uA), d = s.dot(vA), a2 = cone.a * cone.a, b2 = cone.b * cone.b;
  const double D = b2 * c * c + a2 * d * d;
  const double R = cone.a * cone.b / std::sqrt(D);
  *bound = R;
  *row = -s;
  // s turns about tA at rate phi' = (tB x s) . w / sin(swing); R changes by grad R . (tA x s).
  const double sin_swing = tA.cross(tB).norm();
  if (!(sin_swing > 1e-6)) return;
  const Vec3 grad = (-R / D) * (b2 * c * uA + a2 * d * vA);
  *row += (grad.dot(tA.cross(s)) / sin_swing) * tB.cross(s);
}

struct SwingTwistPart {
  SwingTwist angles;  // at the current substep poses
  double cone_bound = 0.0;           // R, the cone's half-angle towards the swing (swing_valid)
  Vec3 cone_row = Vec3::Zero();      // J
  double cone_impulse = 0.0;
  AngleLimitPart twist;

  void update(const Quat& frame_a, const Quat& frame_b, const Vec3& axis, const SwingCone& cone) {
    angles = swingTwist(frame_a, frame_b, axis);
    if (!angles.swing_valid) cone_impulse = 0.0;
    if (!angles.twist_valid) twist = AngleLimitPart();
    if (!angles.swing_valid) return;
    if (!cone.elliptic) {
      cone_bound = cone.a;
      cone_row = -angles.swing_row;
    } else {
      swingConeRow(cone, angles, frame_a * cone.u, frame_a * cone.v, frame_a * axis,
                   frame_b * axis, &cone_bound, &cone_row);
    }
  }

  void warmStart(SolverBody& A, SolverBody& B) const {
    if (angles.swing_valid) applyPairAngularImpulse(A, B, cone_impulse * cone_row);
    if (angles.twist_valid) twist.warmStart(A, B, angles.twist_row);
  }

  void solve(SolverBody& A, SolverBody& B, double twist_lower, double twist_upper,
             const StepContext& ctx, bool use_bias) {
    if (angles.twist_valid)
      twist.solve(A, B, angles.twist_row, AngularRow(angles.twist_row, A, B).k, angles.twist,
                  twist_lower, twist_upper, ctx, use_bias);
    if (angles.swing_valid)
      solveInequalityRow(A, B, AngularRow(cone_row, A, B), cone_bound - angles.swing, cone_impulse,
                         ctx, use_bias);
  }

  // After update() at the current poses.
  bool project(SolverBody& A, SolverBody& B, double twist_lower, double twist_upper, double slop,
               double max_correction) const {
    bool moved = false;
    if (angles.twist_valid)
      moved = AngleLimitPart::project(A, B, angles.twist_row, AngularRow(angles.twist_row, A, B).k,
                                      angles.twist, twist_lower, twist_upper, slop, max_correction);
    if (angles.swing_valid) {
      const Vec3 j = -cone_row;
      moved |= AngleLimitPart::project(A, B, j, AngularRow(j, A, B).k, angles.swing,
                                       -std::numeric_limits<double>::infinity(), cone_bound, slop,
                                       max_correction);
    }
    return moved;
  }
};

}  // namespace ragdoll_sim
