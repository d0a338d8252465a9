// Ball joint: anchor (joint_anchor.hpp) + a motor and an optional limit per Euler angle
// (joint_angle_axes.hpp), or, in limit_mode SwingTwist, a cone and a twist range
// (part_swing_twist.hpp) with the motors still on the Euler angles. Angles and rows:
// joint_angles.hpp.
#pragma once

#include <array>
#include <vector>

#include "joint_anchor.hpp"
#include "joint_angle_axes.hpp"
#include "joint_angles.hpp"
#include "part_swing_twist.hpp"

namespace ragdoll_sim {

struct BallJoint {
  explicit BallJoint(const BallJointDef& def);

  EulerBasis euler;
  AngleAxes<3> axes;  // limits_enabled: Euler limits
  AnchorPart anchor;

  // The kernel job that writes the Euler angles and rows at the frames `in` into axes (*ok: 0
  // near gimbal lock, the rows left), as HingeJoint::angleJob.
  EulerAngleJob angleJob(const JointFrameInputs& in, double* ok) {
    return {in, euler.qP.coeffs().data(), &euler.s, axes.angles.data(), axes.rows[0].data(), ok};
  }

  // Swing-twist limits: cone about twist_axis (joint frame) and twist range.
  bool swing_twist_limits = false;
  Vec3 twist_axis = Vec3::UnitX();
  SwingCone cone;
  double twist_lower = 0.0, twist_upper = 0.0;
  SwingTwistPart swing_twist;

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

  std::array<double, 3> eulerAngles(const JointBase& j, const std::vector<BodyMotion>& m) const;
  std::array<double, 2> swingTwistAngles(const JointBase& j,
                                         const std::vector<BodyMotion>& m) const;

 private:
  // The angles (and the swing-twist rows) at the current substep poses.
  void updateAngles(const JointBase& j, const SolverBody& A, const SolverBody& B,
                    const StepContext& ctx);
  bool limitsClear(double margin) const;
};

}  // namespace ragdoll_sim
