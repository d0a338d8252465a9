// Linear motor part: drives the slide position s = a . d of a prismatic joint with the motor
// row of part_rows.hpp on the LinearRow along the axis a (JointMotor read as linear: target in
// m, target_velocity in m/s, max_torque as the force cap in N, damping in N s/m):
//   position target (hertz > 0): soft row on C = s - target;
//   velocity target (hertz = 0): s_dot -> target_velocity;
//   accumulated impulse clamped to +-max_force h; viscous damping implicit over the substep,
//   its impulse accumulated over the substep's sweeps only.
#pragma once

#include "part_rows.hpp"

namespace ragdoll_sim {

struct LinearMotorPart {
  double impulse = 0.0;          // the drive's, warm-started
  double damping_impulse = 0.0;  // this substep's viscous damping (solveMotorRow)

  void warmStart(SolverBody& A, SolverBody& B, const LinearRow& row) {
    damping_impulse = 0.0;
    row.apply(A, B, impulse);
  }

  void solve(SolverBody& A, SolverBody& B, const LinearRow& row, double s,
             const JointMotor& motor, const StepContext& ctx) {
    solveMotorRow(A, B, row, s, motor, impulse, damping_impulse, ctx);
  }
};

}  // namespace ragdoll_sim
