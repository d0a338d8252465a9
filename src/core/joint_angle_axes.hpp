// The joint angles of a hinge (1) or a ball joint (3 Euler angles), each with a motor
// (part_angle_motor.hpp) and an optional limit (part_angle_limit.hpp) on one angular row.
// The type computes the angles and their world Jacobian rows (joint_hinge.cpp,
// joint_ball.cpp; derivations in joint_angles.hpp); this solves, advances and projects them.
// The rows are computed at warm start, reused by the biased solve (the poses have not moved in
// between), advanced for the relax pass and recomputed by the projection.
#pragma once

#include <array>
#include <cmath>
#include <limits>

#include "part_angle_limit.hpp"
#include "part_angle_motor.hpp"

namespace ragdoll_sim {

template <int N>
struct AngleAxes {
  bool limits_enabled = false;
  // The sweeps leave the motor and limit rows to the wide pass (point_lanes.hpp), set per step.
  bool in_lanes = false;
  // This step's exact angles are computed with other joints' (PointLanes::exactAngles), by the
  // rule of recomputes; set per step.
  bool exact_in_lanes = false;
  // The first substep's exact angles, rows and masses were computed with the island's other
  // joints (firstSubstepAngles, joint.cpp); the warm start takes them and clears the mark.
  bool batched = false;
  std::array<JointMotor, N> motors;
  std::array<double, N> lower{}, upper{};
  std::array<AngleMotorPart, N> motor_parts;
  std::array<AngleLimitPart, N> limits;

  // Angles and rows at the current substep poses (count 0: none, or a ball near gimbal lock).
  int count = 0;
  std::array<double, N> angles{};
  std::array<Vec3, N> rows;
  std::array<double, N> k{};  // row^T (IA^-1 + IB^-1) row
  // Set when the type recomputes the angles and rows, cleared when the wide pass takes them
  // (PointLanes::load): between substeps the lanes otherwise hold what they would copy.
  bool fresh = false;

  bool motorsActive() const {  // a drive or viscous damping on some axis
    for (const JointMotor& m : motors)
      if (m.enabled || m.damping > 0.0) return true;
    return false;
  }
  bool rowsNeeded() const { return limits_enabled || motorsActive(); }

  // After the type set count, angles and rows.
  void updateMass(const SolverBody& A, const SolverBody& B) {
    if (count == 0) return;
    const Mat3 I = A.inv_inertia + B.inv_inertia;
    for (int i = 0; i < count; ++i) k[i] = rows[i].dot(I * rows[i]);
  }

  // After the first substep of a step, axes whose limits are all open (no impulse carried) and
  // at least kOpenMargin away along the advanced angles, and which stay so at their current
  // rate over the substep, keep the advanced angles and last substep's rows instead of
  // recomputing them: their limit rows take the speculative early exit (C > 0, nothing
  // accumulated, C + h rate >= 0) with either, so they apply nothing. Motors read the angles
  // and rows themselves and always recompute. The first substep recomputes: the projection of
  // the previous step moved the bodies without advancing the angles.
  static constexpr double kOpenMargin = 0.05;  // rad, >> the first-order error of the advance

  bool limitsOpen(const SolverBody& A, const SolverBody& B, double h) const {
    if (count == 0 || !limits_enabled || motorsActive()) return false;
    const Vec3 dw = B.w - A.w;
    for (int i = 0; i < count; ++i) {
      const AngleLimitPart& l = limits[i];
      if (l.lower_impulse != 0.0 || l.upper_impulse != 0.0) return false;
      const double travel = h * std::abs(rows[i].dot(dw));
      if (angles[i] - lower[i] < kOpenMargin + travel ||
          upper[i] - angles[i] < kOpenMargin + travel)
        return false;
    }
    return true;
  }

  // Whether a substep's warm start computes the angles and rows exactly: at the first substep
  // (the last step's projection moved the bodies), later unless limitsOpen.
  bool recomputes(const SolverBody& A, const SolverBody& B, double h, bool first_substep) const {
    return first_substep || !limitsOpen(A, B, h);
  }

  void warmStart(SolverBody& A, SolverBody& B) {
    if (in_lanes) return;
    for (int i = 0; i < count; ++i) {
      motor_parts[i].warmStart(A, B, rows[i]);
      if (limits_enabled) limits[i].warmStart(A, B, rows[i]);
    }
  }

  void solve(SolverBody& A, SolverBody& B, const StepContext& ctx, bool use_bias) {
    if (in_lanes) return;
    for (int i = 0; i < count; ++i) {
      const Vec3& row = rows[i];
      motor_parts[i].solve(A, B, row, k[i], angles[i], motors[i], ctx);
      if (limits_enabled)
        limits[i].solve(A, B, row, k[i], angles[i], lower[i], upper[i], ctx, use_bias);
    }
  }

  // The relax pass comes right after the position update: the angles moved by h theta_dot
  // (first order; the rows are kept). Exact angles are recomputed at the next warm start.
  void advance(const SolverBody& A, const SolverBody& B, double h) {
    const Vec3 dw = B.w - A.w;
    for (int i = 0; i < count; ++i) angles[i] += h * rows[i].dot(dw);
  }

  // The angles the substeps left (advanced to first order after the last position update,
  // within ~1e-5 rad) say whether an exact recompute can find anything beyond the slop; most
  // joints are well inside their ranges and skip the trigonometry.
  bool limitsClear(double margin) const {
    if (!limits_enabled) return true;
    if (count == 0) return false;  // near gimbal lock: no rows, look again
    for (int i = 0; i < count; ++i)
      if (rangeExcess(angles[i], lower[i], upper[i], margin) != 0.0) return false;
    return true;
  }

  // After the type recomputed the angles and rows exactly.
  bool project(SolverBody& A, SolverBody& B, double slop, double max_turn) const {
    bool moved = false;
    if (limits_enabled)
      for (int i = 0; i < count; ++i)
        moved |= AngleLimitPart::project(A, B, rows[i], k[i], angles[i], lower[i], upper[i], slop,
                                         max_turn);
    return moved;
  }

  void scaleImpulses(double s) {
    for (AngleLimitPart& l : limits) {
      l.lower_impulse *= s;
      l.upper_impulse *= s;
    }
    for (AngleMotorPart& m : motor_parts) m.impulse *= s;
  }
  void clearWarmStart() {
    limits = {};
    motor_parts = {};
  }
};

}  // namespace ragdoll_sim
