// Hinge joint: anchor (joint_anchor.hpp) + hinge-axis part (part_hinge_axis.hpp, 2 angular
// rows) + a motor and an optional limit on the hinge angle (joint_angle_axes.hpp; the angle
// and its row: joint_angles.hpp, hingeAngle).
#pragma once

#include <vector>

#include "joint_anchor.hpp"
#include "joint_angle_axes.hpp"
#include "joint_angles.hpp"
#include "part_hinge_axis.hpp"

namespace ragdoll_sim {

struct HingeJoint {
  explicit HingeJoint(const HingeJointDef& def);

  Vec3 axis = Vec3::UnitZ();  // joint frame
  Vec3 perp;                  // anyPerpendicular(axis), the angle's reference (hingeAngle)
  Vec3 axis_in_a, axis_in_b;  // the axis in the link frames (the joint frames are fixed in them)
  AngleAxes<1> axes;
  HingeAxisPart hinge_axis;
  AnchorPart anchor;

  // The kernel job that writes the angle and its row at the frames `in` into axes, for the
  // joints whose angles are computed together (PointLanes::exactAngles, firstSubstepAngles).
  HingeAngleJob angleJob(const JointFrameInputs& in) {
    return {in, axis.data(), perp.data(), axes.rows[0].data(), &axes.angles[0]};
  }

  void prepare(JointBase& j, const StepContext& ctx);
  void warmStart(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                 bool first_substep);
  void solve(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx, bool use_bias);
  void finishSubstep(JointBase& j, const StepContext& ctx) const { anchor.setForce(j, ctx); }
  void advance(JointBase& j, const SolverBody& A, const SolverBody& B, const StepContext& ctx);
  bool projectLimits(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx);
  bool projectAnchor(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx) const {
    return anchor.project(j, A, B, ctx);
  }
  void scaleImpulses(double s);
  void clearWarmStart();
  JointMotor& motorAt(int axis) { return axes.motors.at(axis); }

  double angle(const JointBase& j, const std::vector<BodyMotion>& m) const;

 private:
  // The angle and its row at the current substep poses (none without a limit or motor).
  void updateAngle(const JointBase& j, const SolverBody& A, const SolverBody& B,
                   const StepContext& ctx);
};

}  // namespace ragdoll_sim
