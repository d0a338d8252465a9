// Prismatic joint: motor and limit along the axis (part_linear_motor.hpp,
// part_linear_limit.hpp), rotation lock (part_angle_lock.hpp, 3 rows), then the off-axis rows
// (part_point_on_line.hpp, 2 rows) last, as the anchor of the other joints is solved last.
// All rows share the slider geometry of part_slider_frame.hpp, recomputed at every call from
// the bodies' deltas. break_force caps the off-axis force; the joint also breaks when the total
// force (off-axis + axial limit / motor) passes it.
#pragma once

#include <vector>

#include "joint_base.hpp"
#include "part_angle_lock.hpp"
#include "part_linear_limit.hpp"
#include "part_linear_motor.hpp"
#include "part_point_on_line.hpp"
#include "part_slider_frame.hpp"

namespace ragdoll_sim {

struct PrismaticJoint {
  explicit PrismaticJoint(const PrismaticJointDef& def);

  Vec3 axis = Vec3::UnitX();  // joint frame of A
  Vec3 off_axis_in_a = Vec3::UnitY();  // link frame of A: the line part's first row
  bool limit_enabled = false;
  double lower = 0.0, upper = 0.0;  // m
  JointMotor motor;             // linear (PrismaticJointDef::motor)

  SliderFrame slider;
  LinearMotorPart linear_motor;
  LinearLimitPart linear_limit;
  AngleLockPart angle_lock;
  PointOnLinePart line;

  void prepare(JointBase& j, const StepContext& ctx);
  void warmStart(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                 bool first_substep);
  void solve(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx, bool use_bias);
  void finishSubstep(JointBase& j, const StepContext& ctx) const {}  // solve() sets the force
  void advance(JointBase& j, const SolverBody& A, const SolverBody& B, const StepContext& ctx) {}
  bool projectLimits(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx);
  bool projectAnchor(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx) const;
  void scaleImpulses(double s);
  void clearWarmStart();
  JointMotor& motorAt(int axis);

  // Link-frame anchors at the poses m: the position along the axis, and the anchor error
  // (B - A) without its part along the axis.
  double position(const JointBase& j, const std::vector<BodyMotion>& m) const;
  Vec3 offAxis(const JointBase& j, const std::vector<BodyMotion>& m, const Vec3& e) const;
};

}  // namespace ragdoll_sim
