// Angle motor part: drives one joint angle theta (rate theta_dot = j . (wB - wA)) with the
// motor row of part_rows.hpp (m_eff = 1 / (j^T (IA^-1 + IB^-1) j)):
//   position target (hertz > 0): soft row on C = theta - target;
//   velocity target (hertz = 0): theta_dot -> target_velocity;
//   the accumulated impulse is clamped to +-max_torque h (a motor has finite strength);
//   viscous damping c (torque -c theta_dot), implicit over the substep, its impulse accumulated
//   over the substep's sweeps only.
#pragma once

#include "part_rows.hpp"

namespace ragdoll_sim {

struct AngleMotorPart {
  double impulse = 0.0;          // the drive's, warm-started
  double damping_impulse = 0.0;  // this substep's viscous damping (solveMotorRow)

  void warmStart(SolverBody& A, SolverBody& B, const Vec3& j) {
    damping_impulse = 0.0;
    if (impulse != 0.0) applyPairAngularImpulse(A, B, impulse * j);  // no motor: nothing to apply
  }

  // k = j^T (IA^-1 + IB^-1) j, computed with the row.
  void solve(SolverBody& A, SolverBody& B, const Vec3& j, double k, double theta,
             const JointMotor& motor, const StepContext& ctx) {
    if (!motor.enabled && !(motor.damping > 0.0)) return;
    solveMotorRow(A, B, AngularRow(j, k), theta, motor, impulse, damping_impulse, ctx);
  }
};

}  // namespace ragdoll_sim
