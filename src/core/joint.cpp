// Dispatch on joint type, and the anchor shared by all types (rigid or spring).
#include "joint.hpp"

namespace ragdoll_sim {

void warmStartAnchor(Joint& j, SolverBody& A, SolverBody& B) {
  if (j.spring.stiffness > 0.0) return;
  j.point.warmStart(A, B);
}

void solveAnchor(Joint& j, SolverBody& A, SolverBody& B, const StepContext& ctx, bool use_bias) {
  if (j.spring.stiffness > 0.0) {
    if (use_bias) j.force = j.point.solveSpring(A, B, j.spring.stiffness, j.spring.damping, ctx.h);
    return;
  }
  const double max_impulse = j.spring.break_force * ctx.h;
  if (j.point.solve(A, B, ctx.joint_softness, use_bias, max_impulse)) j.overloaded = true;
  j.force = j.point.impulse.norm() * ctx.inv_h;
}

void prepareJoint(Joint& j, const StepContext& ctx) {
  if (j.type == JointType::Ball) prepareBallJoint(j, ctx);
  else prepareHingeJoint(j, ctx);
}

void warmStartJoint(Joint& j, const StepContext& ctx) {
  if (j.type == JointType::Ball) warmStartBallJoint(j, ctx);
  else warmStartHingeJoint(j, ctx);
}

void solveJoint(Joint& j, const StepContext& ctx, bool use_bias) {
  if (j.type == JointType::Ball) solveBallJoint(j, ctx, use_bias);
  else solveHingeJoint(j, ctx, use_bias);
}

}  // namespace ragdoll_sim
