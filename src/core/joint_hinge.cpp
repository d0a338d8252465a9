#include "joint_hinge.hpp"

namespace ragdoll_sim {

HingeJoint::HingeJoint(const HingeJointDef& def)
    : axis(def.axis.normalized()),
      perp(anyPerpendicular(axis)),
      axis_in_a(def.frame_a.q * axis),
      axis_in_b(def.frame_b.q * axis) {
  axes.limits_enabled = def.enable_limit;
  axes.lower[0] = def.lower;
  axes.upper[0] = def.upper;
  axes.motors[0] = def.motor;
}

void HingeJoint::prepare(JointBase& j, const StepContext& ctx) {
  const auto& m = *ctx.motions;
  axes.in_lanes = axes.exact_in_lanes = false;
  anchor.prepare(j, ctx);
  hinge_axis.prepare(m[j.a], m[j.b], axis_in_a, axis_in_b);
}

void HingeJoint::updateAngle(const JointBase& j, const SolverBody& A, const SolverBody& B,
                             const StepContext& ctx) {
  axes.count = 0;
  axes.fresh = true;
  if (!axes.rowsNeeded()) return;
  axes.angles[0] = hingeAngle(currentFrames(j, A, B, *ctx.motions), axis, perp, &axes.rows[0]);
  axes.count = 1;
  axes.updateMass(A, B);
}

// first_substep: the angle and row are recomputed exactly and the anchor and axis refreshed;
// later substeps keep the advanced angle while the limit stays open (AngleAxes::limitsOpen)
// and the anchor and axis advance() refreshed after the last position update: only
// velocities changed since.
void HingeJoint::warmStart(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                           bool first_substep) {
  if (axes.batched) axes.batched = false;
  else if (!axes.exact_in_lanes && axes.recomputes(A, B, ctx.h, first_substep))
    updateAngle(j, A, B, ctx);
  const bool current = !first_substep;
  axes.warmStart(A, B);
  // The axis goes into the lanes with the anchor; there its refresh, K^-1 and warm start are
  // the wide pass's (PointLanes::load).
  if (!anchor.in_lanes) {
    hinge_axis.updateMass(A, B, current);
    hinge_axis.warmStart(A, B);
  }
  anchor.warmStart(j, A, B, ctx, current);
}

void HingeJoint::solve(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                       bool use_bias) {
  axes.solve(A, B, ctx, use_bias);
  if (!anchor.in_lanes) hinge_axis.solve(A, B, ctx.joint_softness, use_bias);
  anchor.solve(j, A, B, ctx, use_bias);
}

void HingeJoint::advance(JointBase& j, const SolverBody& A, const SolverBody& B,
                         const StepContext& ctx) {
  axes.advance(A, B, ctx.h);
  anchor.refresh(A, B);
  hinge_axis.refresh(A, B);
}

bool HingeJoint::projectLimits(JointBase& j, SolverBody& A, SolverBody& B,
                               const StepContext& ctx) {
  const double slop = ctx.settings->angular_slop, max_turn = ctx.settings->max_angular_correction;
  bool moved = false;
  // The axis error refreshed after the last position update (as for limitsClear) screens out
  // the hinges that cannot be beyond the slop.
  if (hinge_axis.C.norm() > 0.5 * slop) moved = hinge_axis.project(A, B, slop, max_turn);
  if (axes.limitsClear(0.5 * slop)) return moved;
  updateAngle(j, A, B, ctx);
  moved |= axes.project(A, B, slop, max_turn);
  return moved;
}

void HingeJoint::scaleImpulses(double s) {
  axes.scaleImpulses(s);
  anchor.scaleImpulses(s);
  hinge_axis.impulse *= s;
}

void HingeJoint::clearWarmStart() {
  axes.clearWarmStart();
  anchor.clearWarmStart();
  hinge_axis = HingeAxisPart();
}

double HingeJoint::angle(const JointBase& j, const std::vector<BodyMotion>& m) const {
  return hingeAngle(j.frameRotationA(m[j.a].q), j.frameRotationB(m[j.b].q), axis);
}

}  // namespace ragdoll_sim
