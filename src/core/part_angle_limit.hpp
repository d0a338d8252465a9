// Angle limit part: lower <= theta <= upper for one joint angle whose rate is
//   theta_dot = j . (wB - wA)          (j: world row of the joint's angle Jacobian)
// Two inequality rows with accumulated impulses clamped to >= 0:
//   lower: C = theta - lower,  upper: C = upper - theta (rate -j . (wB - wA)),
//   m_eff = 1 / (j^T (IA^-1 + IB^-1) j).
// C > 0 is a speculative row (Box2D v3): bias = C / h lets the joint reach the limit in this
// substep but not cross it, so nothing is applied until the limit would be violated.
// C <= 0 uses the soft bias while pushing out and is rigid in the relax pass.
#pragma once

#include "solver_context.hpp"

namespace ragdoll_sim {

struct AngleLimitPart {
  double lower_impulse = 0.0, upper_impulse = 0.0;

  void warmStart(SolverBody& A, SolverBody& B, const Vec3& j) const {
    applyPairAngularImpulse(A, B, (lower_impulse - upper_impulse) * j);
  }

  void solve(SolverBody& A, SolverBody& B, const Vec3& j, double theta, double lower,
             double upper, const StepContext& ctx, bool use_bias) {
    const double k = j.dot((A.inv_inertia + B.inv_inertia) * j);
    if (!(k > 1e-300)) return;
    const double m = 1.0 / k;
    solveRow(A, B, j, theta - lower, m, lower_impulse, ctx, use_bias);
    solveRow(A, B, -j, upper - theta, m, upper_impulse, ctx, use_bias);
  }

 private:
  static void solveRow(SolverBody& A, SolverBody& B, const Vec3& j, double C, double m,
                       double& acc, const StepContext& ctx, bool use_bias) {
    double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
    if (C > 0.0) {
      bias = C * ctx.inv_h;
    } else if (use_bias) {
      bias = ctx.joint_softness.bias_rate * C;
      mass_scale = ctx.joint_softness.mass_scale;
      impulse_scale = ctx.joint_softness.impulse_scale;
    }
    const double cdot = j.dot(B.w - A.w);
    double lambda = -m * mass_scale * (cdot + bias) - impulse_scale * acc;
    const double next = std::max(acc + lambda, 0.0);
    lambda = next - acc;
    acc = next;
    applyPairAngularImpulse(A, B, lambda * j);
  }
};

}  // namespace ragdoll_sim
