// Joint solve shared by all types: angle motors and limits on the joint's angles, type-specific
// angular rows (hinge axis, swing-twist limits, rotation lock), then the anchor (rigid point
// part or spring). Prismatic joints have no anchor point: joint_prismatic.cpp solves them.
#include "joint.hpp"

#include <limits>

namespace ragdoll_sim {

namespace {
void updateAngles(Joint& j, const StepContext& ctx) {
  j.angle_count = 0;
  if (j.type == JointType::Ball) updateBallAngles(j, ctx);  // also the swing-twist rows
  else if (j.type == JointType::Hinge && j.angleRowsNeeded()) updateHingeAngles(j, ctx);
  if (j.angle_count == 0) return;
  const auto& s = *ctx.bodies;
  const Mat3 I = s[j.a].inv_inertia + s[j.b].inv_inertia;
  for (int i = 0; i < j.angle_count; ++i) j.angle_k[i] = j.angle_rows[i].dot(I * j.angle_rows[i]);
}

// The relax pass comes right after the position update: the angles moved by h theta_dot
// (first order; the rows are kept). Exact angles are recomputed at the next warm start.
// Swing-twist limits recompute exactly (their rows turn with the swing plane).
void advanceAngles(Joint& j, const SolverBody& A, const SolverBody& B, const StepContext& ctx) {
  if (j.swing_twist_limits) return updateAngles(j, ctx);
  const Vec3 dw = B.w - A.w;
  for (int i = 0; i < j.angle_count; ++i) j.angles[i] += ctx.h * j.angle_rows[i].dot(dw);
}

// After the first substep of a step, a joint whose limits are all open (no impulse carried) and
// at least kOpenMargin away along the advanced angles, and which stays so at its current rate
// over the substep, keeps the advanced angles and last substep's rows instead of recomputing
// them: its limit rows take the speculative early exit (C > 0, nothing accumulated, C + h rate
// >= 0) with either, so they apply nothing. Motors and swing-twist rows read the angles and
// rows themselves and always recompute. The first substep recomputes: the projection of the
// previous step moved the bodies without advancing the angles.
constexpr double kOpenMargin = 0.05;  // rad, >> the first-order error of the advanced angles

bool limitsOpen(const Joint& j, const SolverBody& A, const SolverBody& B, double h) {
  if (j.angle_count == 0 || !j.limits_enabled || j.swing_twist_limits || j.motorsActive())
    return false;
  const Vec3 dw = B.w - A.w;
  for (int i = 0; i < j.angle_count; ++i) {
    const AngleLimitPart& l = j.limits[i];
    if (l.lower_impulse != 0.0 || l.upper_impulse != 0.0) return false;
    const double travel = h * std::abs(j.angle_rows[i].dot(dw));
    if (j.angles[i] - j.lower[i] < kOpenMargin + travel ||
        j.upper[i] - j.angles[i] < kOpenMargin + travel)
      return false;
  }
  return true;
}

void warmStartAnchor(Joint& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                     bool anchors_current) {
  const double k = j.spring.stiffness;
  j.point.updateMass(A, B, k > 0.0 ? PointPart::springGamma(k, j.spring.damping, ctx.h) : 0.0,
                     anchors_current);
  if (k > 0.0) return;
  j.point.warmStart(A, B);
}

// The anchor: rigid point part, or a Hooke spring (solved once per substep, in the biased pass).
void solveAnchor(Joint& j, SolverBody& A, SolverBody& B, const StepContext& ctx, bool use_bias) {
  if (j.spring.stiffness > 0.0) {
    if (use_bias) j.force = j.point.solveSpring(A, B, j.spring.stiffness, j.spring.damping, ctx.h);
    return;
  }
  const double max_impulse = j.spring.break_force * ctx.h;
  if (j.point.solve(A, B, ctx.joint_softness, use_bias, max_impulse)) j.overloaded = true;
}
// Every part's accumulated impulse times s (warmStartScale, solver_context.hpp).
void scaleImpulses(Joint& j, double s) {
  j.point.impulse *= s;
  j.hinge_axis.impulse *= s;
  for (AngleLimitPart* l : {&j.limits[0], &j.limits[1], &j.limits[2], &j.swing_twist.twist}) {
    l->lower_impulse *= s;
    l->upper_impulse *= s;
  }
  for (AngleMotorPart& m : j.motor_parts) m.impulse *= s;
  j.swing_twist.cone_impulse *= s;
  j.angle_lock.impulse *= s;
  j.line.impulse *= s;
  j.linear_limit.lower_impulse *= s;
  j.linear_limit.upper_impulse *= s;
  j.linear_motor.impulse *= s;
}
}  // namespace

void prepareJoint(Joint& j, const StepContext& ctx) {
  j.moved_sweep = 0;
  if (j.impulse_h != ctx.h) {
    scaleImpulses(j, warmStartScale(j.impulse_h, ctx.h));
    j.impulse_h = ctx.h;
  }
  switch (j.type) {
    case JointType::Ball: prepareBallJoint(j, ctx); break;
    case JointType::Hinge: prepareHingeJoint(j, ctx); break;
    case JointType::Fixed: prepareFixedJoint(j, ctx); break;
    case JointType::Prismatic: preparePrismaticJoint(j, ctx); break;
  }
}

void warmStartJoint(Joint& j, const StepContext& ctx, bool first_substep) {
  auto& s = *ctx.bodies;
  SolverBody &A = s[j.a], &B = s[j.b];
  if (j.type == JointType::Prismatic) return warmStartPrismaticJoint(j, A, B);
  if (first_substep || !limitsOpen(j, A, B, ctx.h)) updateAngles(j, ctx);
  // After the first substep the anchors and the hinge axis are the ones advanceJoint refreshed
  // after the last position update: only velocities have changed since.
  const bool current = !first_substep;
  for (int i = 0; i < j.angle_count; ++i) {
    j.motor_parts[i].warmStart(A, B, j.angle_rows[i]);
    if (j.limits_enabled) j.limits[i].warmStart(A, B, j.angle_rows[i]);
  }
  if (j.type == JointType::Hinge) {
    j.hinge_axis.updateMass(A, B, current);
    j.hinge_axis.warmStart(A, B);
  }
  if (j.swing_twist_limits) j.swing_twist.warmStart(A, B);
  if (j.type == JointType::Fixed) j.angle_lock.warmStart(A, B);
  warmStartAnchor(j, A, B, ctx, current);
}

void solveJoint(Joint& j, const StepContext& ctx, bool use_bias) {
  auto& s = *ctx.bodies;
  SolverBody &A = s[j.a], &B = s[j.b];
  if (j.type == JointType::Prismatic) return solvePrismaticJoint(j, A, B, ctx, use_bias);
  for (int i = 0; i < j.angle_count; ++i) {
    const Vec3& row = j.angle_rows[i];
    const double k = j.angle_k[i];
    j.motor_parts[i].solve(A, B, row, k, j.angles[i], j.motors[i], ctx, use_bias);
    if (j.limits_enabled)
      j.limits[i].solve(A, B, row, k, j.angles[i], j.lower[i], j.upper[i], ctx, use_bias);
  }
  if (j.type == JointType::Hinge) j.hinge_axis.solve(A, B, ctx.joint_softness, use_bias);
  if (j.swing_twist_limits)
    j.swing_twist.solve(A, B, j.swing_cone, j.twist_lower, j.twist_upper, ctx, use_bias);
  if (j.type == JointType::Fixed) {
    // Gauss-Seidel against the anchor overshoots on the way (a long lever on a light body):
    // the weld breaks when the torque still sits at the cap after the substep's last sweep.
    j.angle_lock.solve(A, B, ctx.joint_softness, use_bias, j.spring.break_torque * ctx.h);
    j.torque = j.angle_lock.impulse.norm() * ctx.inv_h;
  }
  solveAnchor(j, A, B, ctx, use_bias);
}

bool breaksAfterSubstep(Joint& j, const StepContext& ctx) {
  if (j.broken) return false;
  // A rigid anchor's force is its impulse accumulated over the substep (a spring's and a
  // prismatic joint's are set by their solve).
  if (j.type != JointType::Prismatic && !(j.spring.stiffness > 0.0))
    j.force = j.point.impulse.norm() * ctx.inv_h;
  return j.overloaded || j.force > j.spring.break_force ||
         j.torque >= (1.0 - 1e-9) * j.spring.break_torque;
}

// After the position update: the relax sweeps see the moved anchors and axes.
void advanceJoint(Joint& j, const StepContext& ctx) {
  if (j.type == JointType::Prismatic) return;
  auto& s = *ctx.bodies;
  const SolverBody &A = s[j.a], &B = s[j.b];
  advanceAngles(j, A, B, ctx);
  j.point.refresh(A, B);
  if (j.type == JointType::Hinge) j.hinge_axis.refresh(A, B);
}

// The angles the substeps left (advanced to first order after the last position update,
// within ~1e-5 rad) say whether an exact recompute can find anything beyond the slop; most
// joints are well inside their ranges and skip the trigonometry.
namespace {
bool limitsClear(const Joint& j, double margin) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (j.limits_enabled) {
    if (j.angle_count == 0) return false;  // near gimbal lock: no rows, look again
    for (int i = 0; i < j.angle_count; ++i)
      if (rangeExcess(j.angles[i], j.lower[i], j.upper[i], margin) != 0.0) return false;
  }
  if (j.swing_twist_limits) {
    const SwingTwist& st = j.swing_twist.angles;
    if (rangeExcess(st.swing, -kInf, j.swing_cone, margin) != 0.0 ||
        rangeExcess(st.twist, j.twist_lower, j.twist_upper, margin) != 0.0)
      return false;
  }
  return true;
}
}  // namespace

bool projectJointLimits(Joint& j, const StepContext& ctx) {
  if (j.broken) return false;
  const double slop = ctx.def->angular_slop, max_turn = ctx.def->max_angular_correction;
  auto& s = *ctx.bodies;
  SolverBody &A = s[j.a], &B = s[j.b];
  bool moved = false;
  if (j.type == JointType::Fixed || j.type == JointType::Prismatic)
    moved = j.angle_lock.project(A, B, slop, max_turn);
  if (j.type == JointType::Prismatic) {
    if (j.limits_enabled)
      moved |= LinearLimitPart::project(A, B, j.slider.at(A, B), j.lower[0], j.upper[0],
                                        ctx.def->joint_slop, ctx.def->max_position_correction);
    return moved;
  }
  // The axis error refreshed after the last position update (as for limitsClear) screens out
  // the hinges that cannot be beyond the slop.
  if (j.type == JointType::Hinge && j.hinge_axis.C.norm() > 0.5 * slop)
    moved |= j.hinge_axis.project(A, B, slop, max_turn);
  if (!(j.limits_enabled || j.swing_twist_limits) || limitsClear(j, 0.5 * slop)) return moved;
  updateAngles(j, ctx);
  if (j.limits_enabled)
    for (int i = 0; i < j.angle_count; ++i)
      moved |= AngleLimitPart::project(A, B, j.angle_rows[i], j.angle_k[i], j.angles[i],
                                       j.lower[i], j.upper[i], slop, max_turn);
  if (j.swing_twist_limits)
    moved |= j.swing_twist.project(A, B, j.swing_cone, j.twist_lower, j.twist_upper, slop,
                                   max_turn);
  return moved;
}

bool projectJointAnchor(Joint& j, const StepContext& ctx) {
  if (j.broken) return false;
  auto& s = *ctx.bodies;
  SolverBody &A = s[j.a], &B = s[j.b];
  const double slop = ctx.def->joint_slop, max_move = ctx.def->max_position_correction;
  if (j.type == JointType::Prismatic)
    return j.line.project(A, B, j.slider.at(A, B), slop, max_move);
  if (j.spring.stiffness > 0.0) return false;  // a spring anchor is meant to stretch
  return j.point.project(A, B, max_move, slop);
}

}  // namespace ragdoll_sim
