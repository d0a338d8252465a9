// Prismatic joint: motor and limit along the axis (part_linear_motor.hpp,
// part_linear_limit.hpp), rotation lock (part_angle_lock.hpp, 3 rows), then the off-axis rows
// (part_point_on_line.hpp, 2 rows) last, as the anchor of the other joints is solved last.
// All rows share the slider geometry of part_slider_frame.hpp, recomputed at every call from
// the bodies' deltas. break_force caps the off-axis force; the joint also breaks when the total
// force (off-axis + axial limit / motor) passes it.
#include "joint.hpp"

namespace ragdoll_sim {

void preparePrismaticJoint(Joint& j, const StepContext& ctx) {
  const auto& m = *ctx.motions;
  j.slider.prepare(m[j.a], m[j.b], j.frame_a.p, j.frame_b.p, j.frame_a.q * j.axis);
  j.angle_lock.prepare(j.frameRotationA(m[j.a].q), j.frameRotationB(m[j.b].q));
}

void warmStartPrismaticJoint(Joint& j, SolverBody& A, SolverBody& B) {
  const SliderPose p = j.slider.at(A, B);
  const LinearRow row(p.axis, p.leverA(), p.rB, A, B);
  j.linear_motor.warmStart(A, B, row);
  if (j.limits_enabled) j.linear_limit.warmStart(A, B, row);
  j.angle_lock.warmStart(A, B);
  j.line.warmStart(A, B, p);
}

void solvePrismaticJoint(Joint& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                         bool use_bias) {
  const SliderPose p = j.slider.at(A, B);
  const LinearRow row(p.axis, p.leverA(), p.rB, A, B);
  const double s = p.position();
  j.linear_motor.solve(A, B, row, s, j.motors[0], ctx, use_bias);
  if (j.limits_enabled)
    j.linear_limit.solve(A, B, row, s, j.lower[0], j.upper[0], ctx, use_bias);
  j.angle_lock.solve(A, B, ctx.joint_softness, use_bias);
  const double max_impulse = j.spring.break_force * ctx.h;
  if (j.line.solve(A, B, p, ctx.joint_softness, use_bias, max_impulse)) j.overloaded = true;
  const double axial = j.linear_motor.impulse + j.linear_limit.lower_impulse -
                       j.linear_limit.upper_impulse;
  j.force = (j.line.force(p) + axial * p.axis).norm() * ctx.inv_h;
}

}  // namespace ragdoll_sim
