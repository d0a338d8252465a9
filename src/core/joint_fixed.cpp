#include "joint_fixed.hpp"

namespace ragdoll_sim {

void FixedJoint::prepare(JointBase& j, const StepContext& ctx) {
  const auto& m = *ctx.motions;
  anchor.prepare(j, ctx);
  angle_lock.prepare(j.frameRotationA(m[j.a].q), j.frameRotationB(m[j.b].q));
}

void FixedJoint::warmStart(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                           bool first_substep) {
  angle_lock.warmStart(A, B);
  anchor.warmStart(j, A, B, ctx, !first_substep);
}

void FixedJoint::solve(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                       bool use_bias) {
  // Gauss-Seidel against the anchor overshoots on the way (a long lever on a light body): the
  // weld breaks when the torque still sits at the cap after the substep's last sweep.
  angle_lock.solve(A, B, ctx.joint_softness, use_bias, j.spring.break_torque * ctx.h);
  j.torque = angle_lock.impulse.norm() * ctx.inv_h;
  anchor.solve(j, A, B, ctx, use_bias);
}

void FixedJoint::scaleImpulses(double s) {
  anchor.scaleImpulses(s);
  angle_lock.impulse *= s;
}

void FixedJoint::clearWarmStart() {
  anchor.clearWarmStart();
  angle_lock = AngleLockPart();
}

}  // namespace ragdoll_sim
