// Joint storage and the per-type solve functions (joint_ball.cpp, joint_hinge.cpp).
// Every joint is composed from constraint parts (part_*.hpp) that hold the math.
#pragma once

#include <array>

#include "joint_angles.hpp"
#include "part_angle_limit.hpp"
#include "part_angle_motor.hpp"
#include "part_hinge_axis.hpp"
#include "part_point.hpp"
#include "ragdoll_sim/joint.hpp"

namespace ragdoll_sim {

struct Joint {
  JointType type = JointType::Ball;
  int a = -1, b = -1;              // body / solver-body indices
  Transform frame_a, frame_b;      // joint frames in the link frames
  bool limits_enabled = false;
  PointPart point;
  JointSpring spring;
  bool broken = false;
  bool overloaded = false;  // the anchor reached break_force in this substep
  double force = 0.0;  // N in the anchor during the last substep
  std::array<JointMotor, 3> motors;       // hinge: [0]; ball: per Euler axis
  std::array<AngleMotorPart, 3> motor_parts;

  // Hinge: axis in the joint frame; limit on its angle.
  Vec3 axis = Vec3::UnitZ();
  double lower = 0.0, upper = 0.0;
  HingeAxisPart hinge_axis;
  AngleLimitPart limit;

  // Ball: Euler basis and per-axis limits.
  EulerBasis euler;
  std::array<double, 3> lower3{}, upper3{};
  std::array<AngleLimitPart, 3> limits3;

  bool angleRowsNeeded() const {
    bool motor = false;
    for (const JointMotor& m : motors) motor |= m.enabled || m.damping > 0.0;
    return limits_enabled || motor;
  }
  Quat frameRotationA(const Quat& qa) const { return qa * frame_a.q; }
  Quat frameRotationB(const Quat& qb) const { return qb * frame_b.q; }
};

void prepareJoint(Joint& j, const StepContext& ctx);
// The anchor: rigid point part, or a Hooke spring (solved once per substep, in the biased pass).
void warmStartAnchor(Joint& j, SolverBody& A, SolverBody& B);
void solveAnchor(Joint& j, SolverBody& A, SolverBody& B, const StepContext& ctx, bool use_bias);
void warmStartJoint(Joint& j, const StepContext& ctx);
void solveJoint(Joint& j, const StepContext& ctx, bool use_bias);

void prepareBallJoint(Joint& j, const StepContext& ctx);
void warmStartBallJoint(Joint& j, const StepContext& ctx);
void solveBallJoint(Joint& j, const StepContext& ctx, bool use_bias);
void prepareHingeJoint(Joint& j, const StepContext& ctx);
void warmStartHingeJoint(Joint& j, const StepContext& ctx);
void solveHingeJoint(Joint& j, const StepContext& ctx, bool use_bias);

}  // namespace ragdoll_sim
