// Fixed joint (weld): anchor (joint_anchor.hpp) + rotation lock (part_angle_lock.hpp, 3
// angular rows) capped at break_torque h, so that the weld breaks when the torque still sits
// at the cap after the substep's last sweep.
#pragma once

#include <stdexcept>

#include "joint_anchor.hpp"
#include "part_angle_lock.hpp"

namespace ragdoll_sim {

struct FixedJoint {
  explicit FixedJoint(const FixedJointDef&) {}

  AngleLockPart angle_lock;
  AnchorPart anchor;

  void prepare(JointBase& j, const StepContext& ctx);
  void warmStart(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                 bool first_substep);
  void solve(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx, bool use_bias);
  void finishSubstep(JointBase& j, const StepContext& ctx) const { anchor.setForce(j, ctx); }
  void advance(JointBase& j, const SolverBody& A, const SolverBody& B, const StepContext& ctx) {
    anchor.refresh(A, B);
  }
  bool projectLimits(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx) {
    return angle_lock.project(A, B, ctx.settings->angular_slop,
                              ctx.settings->max_angular_correction);
  }
  bool projectAnchor(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx) const {
    return anchor.project(j, A, B, ctx);
  }
  void scaleImpulses(double s);
  void clearWarmStart();
  JointMotor& motorAt(int axis) { throw std::out_of_range("a fixed joint has no motor"); }
};

}  // namespace ragdoll_sim
