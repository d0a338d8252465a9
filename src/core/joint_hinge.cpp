// Hinge joint = point part + hinge-axis part (2 angular rows) + (optional) angle-limit part.
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
  if (j.limits_enabled) {
    Vec3 axis;
    double theta;
    hingeLimitRow(j, ctx, axis, theta);
    j.limit.warmStart(A, B, axis);
  }
  j.hinge_axis.warmStart(A, B);
  j.point.warmStart(A, B);
}

void solveHingeJoint(Joint& j, const StepContext& ctx, bool use_bias) {
  auto& s = *ctx.bodies;
  SolverBody &A = s[j.a], &B = s[j.b];
  if (j.limits_enabled) {
    Vec3 axis;
    double theta;
    hingeLimitRow(j, ctx, axis, theta);
    j.limit.solve(A, B, axis, theta, j.lower, j.upper, ctx, use_bias);
  }
  j.hinge_axis.solve(A, B, ctx.joint_softness, use_bias);
  j.point.solve(A, B, ctx.joint_softness, use_bias);
}

}  // namespace ragdoll_sim
