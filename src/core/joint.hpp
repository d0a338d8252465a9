// Joint storage and the per-type solve functions (joint_ball.cpp, joint_hinge.cpp,
// joint_fixed.cpp, joint_prismatic.cpp). Every joint is composed from constraint parts
// (part_*.hpp) that hold the math.
#pragma once

#include <array>

#include "joint_angles.hpp"
#include "part_angle_limit.hpp"
#include "part_angle_lock.hpp"
#include "part_angle_motor.hpp"
#include "part_hinge_axis.hpp"
#include "part_linear_limit.hpp"
#include "part_linear_motor.hpp"
#include "part_point.hpp"
#include "part_point_on_line.hpp"
#include "part_slider_frame.hpp"
#include "part_swing_twist.hpp"
#include "ragdoll_sim/joint.hpp"

namespace ragdoll_sim {

struct Joint {
  JointType type = JointType::Ball;
  int a = -1, b = -1;              // body / solver-body indices
  Transform frame_a, frame_b;      // joint frames in the link frames
  bool limits_enabled = false;     // hinge / ball Euler angles; prismatic: the slide
  PointPart point;
  JointSpring spring;
  bool broken = false;
  bool overloaded = false;  // the anchor reached break_force in this substep
  int moved_sweep = 0;  // the last position sweep of the step in which it moved a body
  double force = 0.0;  // N in the anchor during the last substep
  double torque = 0.0;  // N m in a fixed joint's rotation lock during the last substep
  double impulse_h = 0.0;  // s: the substep the parts' impulses were accumulated over
  std::array<JointMotor, 3> motors;       // hinge, prismatic: [0]; ball: per Euler axis
  std::array<AngleMotorPart, 3> motor_parts;

  // Hinge, prismatic: axis in the joint frame. Ball: Euler basis.
  Vec3 axis = Vec3::UnitZ();
  HingeAxisPart hinge_axis;
  EulerBasis euler;

  // Joint angles (hinge: 1, ball: 3 Euler angles) with their limits and motors; prismatic:
  // lower[0] / upper[0] bound the slide (m).
  std::array<double, 3> lower{}, upper{};
  std::array<AngleLimitPart, 3> limits;

  // Ball, limit_mode SwingTwist: cone about twist_axis (joint frame) and twist range.
  bool swing_twist_limits = false;
  Vec3 twist_axis = Vec3::UnitX();
  double swing_cone = 0.0, twist_lower = 0.0, twist_upper = 0.0;
  SwingTwistPart swing_twist;

  // Fixed, prismatic: relative rotation locked.
  AngleLockPart angle_lock;

  // Prismatic: slider geometry, off-axis rows, limit and motor (motors[0]) along the axis.
  SliderFrame slider;
  PointOnLinePart line;
  LinearLimitPart linear_limit;
  LinearMotorPart linear_motor;

  // Angles and their world Jacobian rows at the current substep poses (count 0: none, or a
  // ball near gimbal lock). Computed at warm start, reused by the biased solve (the poses
  // have not moved in between), advanced for the relax pass, recomputed by the projection.
  int angle_count = 0;
  std::array<double, 3> angles{};
  std::array<Vec3, 3> angle_rows;
  std::array<double, 3> angle_k{};  // row^T (IA^-1 + IB^-1) row

  bool motorsActive() const {  // a drive or viscous damping on some axis
    for (const JointMotor& m : motors)
      if (m.enabled || m.damping > 0.0) return true;
    return false;
  }
  bool angleRowsNeeded() const { return limits_enabled || motorsActive(); }
  Quat frameRotationA(const Quat& qa) const { return qa * frame_a.q; }
  Quat frameRotationB(const Quat& qb) const { return qb * frame_b.q; }
};

void prepareJoint(Joint& j, const StepContext& ctx);
// Type-specific: fill angle_count / angles / angle_rows for the current poses.
void updateBallAngles(Joint& j, const StepContext& ctx);
void updateHingeAngles(Joint& j, const StepContext& ctx);
// first_substep: the angles and rows are recomputed exactly, and the anchors and hinge axes
// refreshed; later substeps keep the advanced angles of joints whose limits stay open
// (joint.cpp, limitsOpen) and the anchors and axes advanceJoint refreshed.
void warmStartJoint(Joint& j, const StepContext& ctx, bool first_substep);
void solveJoint(Joint& j, const StepContext& ctx, bool use_bias);
// After a substep's last sweep: sets a rigid anchor's force (N, from its accumulated impulse)
// and says whether the joint breaks (break force or torque passed, or the anchor capped).
bool breaksAfterSubstep(Joint& j, const StepContext& ctx);
// After the position update of a substep, before the relax sweeps: angles advance by h rate.
void advanceJoint(Joint& j, const StepContext& ctx);
// Position projection after the substeps (the error beyond the slops, no velocity added):
// projectJointLimits turns the bodies (rotation lock of fixed and prismatic joints, hinge axis,
// angle limits, swing-twist) and moves a prismatic joint back into its slide range;
// projectJointAnchor moves the rigid anchor (part_point.hpp) or a slider back onto its line. A
// sweep projects every joint's limits before any anchor: a limit turns its bodies about their
// centres, which moves the neighbours' anchors. Both return true when they moved a body.
bool projectJointLimits(Joint& j, const StepContext& ctx);
bool projectJointAnchor(Joint& j, const StepContext& ctx);

void prepareBallJoint(Joint& j, const StepContext& ctx);
void prepareHingeJoint(Joint& j, const StepContext& ctx);
void prepareFixedJoint(Joint& j, const StepContext& ctx);
void preparePrismaticJoint(Joint& j, const StepContext& ctx);
// Prismatic joints solve all their rows (off-axis, lock, limit, motor) here.
void warmStartPrismaticJoint(Joint& j, SolverBody& A, SolverBody& B);
void solvePrismaticJoint(Joint& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                         bool use_bias);

}  // namespace ragdoll_sim
