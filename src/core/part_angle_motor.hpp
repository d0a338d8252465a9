// Angle motor part: drives one joint angle theta (rate theta_dot = j . (wB - wA)).
//   m_eff = 1 / (j^T (IA^-1 + IB^-1) j)
//   position target (hertz > 0): soft row on C = theta - target (softness.hpp),
//     lambda = -mass_scale m_eff (theta_dot + bias_rate C) - impulse_scale lambda_acc;
//   velocity target (hertz = 0): lambda = -m_eff (theta_dot - target_velocity);
//   the accumulated impulse is clamped to +-max_torque h (a motor has finite strength).
//   viscous damping c (torque -c theta_dot), implicit over the substep:
//     lambda = -theta_dot / (1/m_eff + 1/(h c)).
#pragma once

#include <algorithm>

#include "ragdoll_sim/joint.hpp"
#include "solver_context.hpp"

namespace ragdoll_sim {

struct AngleMotorPart {
  double impulse = 0.0;

  void warmStart(SolverBody& A, SolverBody& B, const Vec3& j) const {
    applyPairAngularImpulse(A, B, impulse * j);
  }

  void solve(SolverBody& A, SolverBody& B, const Vec3& j, double theta, const JointMotor& motor,
             const StepContext& ctx, bool use_bias) {
    const double k = j.dot((A.inv_inertia + B.inv_inertia) * j);
    if (!(k > 1e-300)) return;
    const double m = 1.0 / k;
    if (motor.damping > 0.0 && use_bias) {
      const double lambda = -j.dot(B.w - A.w) / (k + 1.0 / (ctx.h * motor.damping));
      applyPairAngularImpulse(A, B, lambda * j);
    }
    if (!motor.enabled) return;
    const double rate = j.dot(B.w - A.w);
    double lambda;
    if (motor.hertz > 0.0) {
      const Softness soft = Softness::make(motor.hertz, motor.damping_ratio, ctx.h);
      lambda = -soft.mass_scale * m * (rate + soft.bias_rate * (theta - motor.target)) -
               soft.impulse_scale * impulse;
    } else {
      lambda = -m * (rate - motor.target_velocity);
    }
    const double max_impulse = motor.max_torque * ctx.h;
    const double next = std::clamp(impulse + lambda, -max_impulse, max_impulse);
    lambda = next - impulse;
    impulse = next;
    applyPairAngularImpulse(A, B, lambda * j);
  }
};

}  // namespace ragdoll_sim
