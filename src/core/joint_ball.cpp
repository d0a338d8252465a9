#include "joint_ball.hpp"

#include <limits>

namespace ragdoll_sim {

BallJoint::BallJoint(const BallJointDef& def) : euler(def.axes) {
  const bool swing_twist_mode = def.limit_mode == BallLimitMode::SwingTwist;
  axes.limits_enabled = def.enable_limits && !swing_twist_mode;
  swing_twist_limits = def.enable_limits && swing_twist_mode;
  twist_axis = def.axes[0].normalized();
  cone.a = def.swing_cone_angle;
  cone.b = def.swing_cone_angle_2;
  cone.elliptic = def.swing_cone_angle_2 > 0.0 && def.swing_cone_angle_2 != def.swing_cone_angle;
  if (cone.elliptic) {
    cone.u = def.axes[1] - twist_axis * twist_axis.dot(def.axes[1]);
    cone.u = cone.u.norm() > 1e-9 ? Vec3(cone.u.normalized()) : anyPerpendicular(twist_axis);
    cone.v = twist_axis.cross(cone.u);
  }
  twist_lower = def.twist_lower;
  twist_upper = def.twist_upper;
  axes.lower = def.lower;
  axes.upper = def.upper;
  axes.motors = def.motors;
}

void BallJoint::prepare(JointBase& j, const StepContext& ctx) {
  axes.in_lanes = axes.exact_in_lanes = false;
  anchor.prepare(j, ctx);
}

void BallJoint::updateAngles(const JointBase& j, const SolverBody& A, const SolverBody& B,
                             const StepContext& ctx) {
  axes.count = 0;
  axes.fresh = true;
  const bool euler_rows = axes.rowsNeeded();
  if (!euler_rows && !swing_twist_limits) return;
  const auto& m = *ctx.motions;
  if (swing_twist_limits)
    swing_twist.update(j.frameRotationA(A.dq * m[j.a].q), j.frameRotationB(B.dq * m[j.b].q),
                       twist_axis, cone);
  if (!euler_rows) return;
  Vec3 t;
  axes.count = euler.angles(currentFrames(j, A, B, m), t, &axes.rows) ? 3 : 0;
  axes.angles = {t[0], t[1], t[2]};
  axes.updateMass(A, B);
}

// first_substep: the angles and rows are recomputed exactly and the anchors refreshed; later
// substeps keep the advanced angles while the limits stay open (AngleAxes::limitsOpen) and the
// anchors advance() refreshed after the last position update: only velocities changed since.
void BallJoint::warmStart(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                          bool first_substep) {
  // Swing-twist rows turn with the swing plane: always recomputed.
  if (axes.batched) axes.batched = false;
  else if (!axes.exact_in_lanes &&
           (swing_twist_limits || axes.recomputes(A, B, ctx.h, first_substep)))
    updateAngles(j, A, B, ctx);
  axes.warmStart(A, B);
  if (swing_twist_limits) swing_twist.warmStart(A, B);
  anchor.warmStart(j, A, B, ctx, !first_substep);
}

void BallJoint::solve(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                      bool use_bias) {
  axes.solve(A, B, ctx, use_bias);
  if (swing_twist_limits)
    swing_twist.solve(A, B, twist_lower, twist_upper, ctx, use_bias);
  anchor.solve(j, A, B, ctx, use_bias);
}

// Swing-twist limits recompute exactly (their rows turn with the swing plane).
void BallJoint::advance(JointBase& j, const SolverBody& A, const SolverBody& B,
                        const StepContext& ctx) {
  if (swing_twist_limits) updateAngles(j, A, B, ctx);
  else axes.advance(A, B, ctx.h);
  anchor.refresh(A, B);
}

bool BallJoint::limitsClear(double margin) const {
  if (!axes.limitsClear(margin)) return false;
  if (!swing_twist_limits) return true;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const SwingTwist& st = swing_twist.angles;
  return rangeExcess(st.swing, -kInf, swing_twist.cone_bound, margin) == 0.0 &&
         rangeExcess(st.twist, twist_lower, twist_upper, margin) == 0.0;
}

bool BallJoint::projectLimits(JointBase& j, SolverBody& A, SolverBody& B,
                              const StepContext& ctx) {
  const double slop = ctx.settings->angular_slop, max_turn = ctx.settings->max_angular_correction;
  if (!(axes.limits_enabled || swing_twist_limits) || limitsClear(0.5 * slop)) return false;
  updateAngles(j, A, B, ctx);
  bool moved = axes.project(A, B, slop, max_turn);
  if (swing_twist_limits)
    moved |= swing_twist.project(A, B, twist_lower, twist_upper, slop, max_turn);
  return moved;
}

void BallJoint::scaleImpulses(double s) {
  axes.scaleImpulses(s);
  anchor.scaleImpulses(s);
  swing_twist.cone_impulse *= s;
  swing_twist.twist.lower_impulse *= s;
  swing_twist.twist.upper_impulse *= s;
}

void BallJoint::clearWarmStart() {
  axes.clearWarmStart();
  anchor.clearWarmStart();
  swing_twist = SwingTwistPart();
}

std::array<double, 3> BallJoint::eulerAngles(const JointBase& j,
                                             const std::vector<BodyMotion>& m) const {
  const Vec3 t = euler.angles(j.frameRotationA(m[j.a].q), j.frameRotationB(m[j.b].q));
  return {t[0], t[1], t[2]};
}

std::array<double, 2> BallJoint::swingTwistAngles(const JointBase& j,
                                                  const std::vector<BodyMotion>& m) const {
  const SwingTwist st =
      swingTwist(j.frameRotationA(m[j.a].q), j.frameRotationB(m[j.b].q), twist_axis);
  return {st.swing, st.twist};
}

}  // namespace ragdoll_sim
