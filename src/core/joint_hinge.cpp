// Hinge joint = anchor (point part or spring) + hinge-axis part (2 angular rows) + optional
// angle-motor and angle-limit parts on the hinge angle.
#include "joint.hpp"

namespace ragdoll_sim {

namespace {
void hingeLimitRow(const Joint& j, const StepContext& ctx, Vec3& axis, double& theta) {
  const auto& m = *ctx.motions;
  const auto& s = *ctx.bodies;
  const Quat fa = j.frameRotationA(s[j.a].dq * m[j.a].q);
  const Quat fb = j.frameRotationB(s[j.b].dq * m[j.b].q);
  axis = fa * j.axis;
  theta = hingeAngle(fa, fb, j.axis);
}
}  // namespace

void prepareHingeJoint(Joint& j, const StepContext& ctx) {
  const auto& m = *ctx.motions;
  j.point.prepare(m[j.a], m[j.b], j.frame_a.p, j.frame_b.p);
  j.hinge_axis.prepare(m[j.a], m[j.b], j.frame_a.q * j.axis, j.frame_b.q * j.axis);
}

void warmStartHingeJoint(Joint& j, const StepContext& ctx) {
  auto& s = *ctx.bodies;
  SolverBody &A = s[j.a], &B = s[j.b];
  if (j.angleRowsNeeded()) {
    Vec3 axis;
    double theta;
    hingeLimitRow(j, ctx, axis, theta);
    j.motor_parts[0].warmStart(A, B, axis);
    if (j.limits_enabled) j.limit.warmStart(A, B, axis);
  }
  j.hinge_axis.warmStart(A, B);
  warmStartAnchor(j, A, B);
}

void solveHingeJoint(Joint& j, const StepContext& ctx, bool use_bias) {
  auto& s = *ctx.bodies;
  SolverBody &A = s[j.a], &B = s[j.b];
  if (j.angleRowsNeeded()) {
    Vec3 axis;
    double theta;
    hingeLimitRow(j, ctx, axis, theta);
    j.motor_parts[0].solve(A, B, axis, theta, j.motors[0], ctx, use_bias);
    if (j.limits_enabled) j.limit.solve(A, B, axis, theta, j.lower, j.upper, ctx, use_bias);
  }
  j.hinge_axis.solve(A, B, ctx.joint_softness, use_bias);
  solveAnchor(j, A, B, ctx, use_bias);
}

}  // namespace ragdoll_sim
