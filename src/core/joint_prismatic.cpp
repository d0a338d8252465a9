#include "joint_prismatic.hpp"

#include <stdexcept>

namespace ragdoll_sim {

PrismaticJoint::PrismaticJoint(const PrismaticJointDef& def)
    : axis(def.axis.normalized()),
      off_axis_in_a(anyPerpendicular(def.frame_a.q * def.axis.normalized())),
      limit_enabled(def.enable_limit), lower(def.lower), upper(def.upper), motor(def.motor) {}

void PrismaticJoint::prepare(JointBase& j, const StepContext& ctx) {
  const auto& m = *ctx.motions;
  slider.prepare(m[j.a], m[j.b], j.frame_a.p, j.frame_b.p, j.frame_a.q * axis, off_axis_in_a);
  angle_lock.prepare(j.frameRotationA(m[j.a].q), j.frameRotationB(m[j.b].q));
}

void PrismaticJoint::warmStart(JointBase& j, SolverBody& A, SolverBody& B,
                               const StepContext& ctx, bool first_substep) {
  const SliderPose p = slider.at(A, B);
  const LinearRow row(p.axis, p.leverA(), p.rB, A, B);
  linear_motor.warmStart(A, B, row);
  if (limit_enabled) linear_limit.warmStart(A, B, row);
  angle_lock.warmStart(A, B);
  line.warmStart(A, B, p);
}

void PrismaticJoint::solve(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                           bool use_bias) {
  const SliderPose p = slider.at(A, B);
  const LinearRow row(p.axis, p.leverA(), p.rB, A, B);
  const double s = p.position();
  linear_motor.solve(A, B, row, s, motor, ctx);
  if (limit_enabled) linear_limit.solve(A, B, row, s, lower, upper, ctx, use_bias);
  angle_lock.solve(A, B, ctx.joint_softness, use_bias);
  const double max_impulse = j.spring.break_force * ctx.h;
  if (line.solve(A, B, p, ctx.joint_softness, use_bias, max_impulse)) j.overloaded = true;
  const double axial = linear_motor.impulse + linear_limit.lower_impulse -
                       linear_limit.upper_impulse;
  j.force = (line.force(p) + axial * p.axis).norm() * ctx.inv_h;
}

bool PrismaticJoint::projectLimits(JointBase& j, SolverBody& A, SolverBody& B,
                                   const StepContext& ctx) {
  const SolverSettings& d = *ctx.settings;
  bool moved = angle_lock.project(A, B, d.angular_slop, d.max_angular_correction);
  if (limit_enabled)
    moved |= LinearLimitPart::project(A, B, slider.at(A, B), lower, upper, d.joint_slop,
                                      d.max_position_correction);
  return moved;
}

bool PrismaticJoint::projectAnchor(JointBase& j, SolverBody& A, SolverBody& B,
                                   const StepContext& ctx) const {
  return line.project(A, B, slider.at(A, B), ctx.settings->joint_slop,
                      ctx.settings->max_position_correction);
}

void PrismaticJoint::scaleImpulses(double s) {
  angle_lock.impulse *= s;
  line.impulse *= s;
  linear_limit.lower_impulse *= s;
  linear_limit.upper_impulse *= s;
  linear_motor.impulse *= s;
}

void PrismaticJoint::clearWarmStart() {
  angle_lock = AngleLockPart();
  line = PointOnLinePart();
  linear_limit = LinearLimitPart();
  linear_motor = LinearMotorPart();
}

JointMotor& PrismaticJoint::motorAt(int axis) {
  if (axis != 0) throw std::out_of_range("a prismatic joint has one motor, axis 0");
  return motor;
}

double PrismaticJoint::position(const JointBase& j, const std::vector<BodyMotion>& m) const {
  const Vec3 d = m[j.b].linkPose().apply(j.frame_b.p) - m[j.a].linkPose().apply(j.frame_a.p);
  return (j.frameRotationA(m[j.a].q) * axis).dot(d);
}

Vec3 PrismaticJoint::offAxis(const JointBase& j, const std::vector<BodyMotion>& m,
                             const Vec3& e) const {
  const Vec3 a = j.frameRotationA(m[j.a].q) * axis;
  return e - a.dot(e) * a;
}

}  // namespace ragdoll_sim
