// One-dimensional constraint rows, shared by the limit and motor parts (angular and linear).
//   angular row j:        Cdot = j . (wB - wA),
//                         k = j^T (IA^-1 + IB^-1) j
//   linear row n, lever arms lA (from A's COM) and rB (from B's):
//                         Cdot = n . (vB - vA) + (rB x n) . wB - (lA x n) . wA,
//                         k = 1/mA + 1/mB + (lA x n)^T IA^-1 (lA x n) + (rB x n)^T IB^-1 (rB x n)
//   (k = J M^-1 J^T); an impulse lambda acts along +J on B and -J on A.
//
// solveInequalityRow: C >= 0, accumulated impulse clamped to >= 0. C > 0 is a speculative row
// (Box2D v3): bias = C / h lets the row reach 0 in this substep but not cross it, so nothing is
// applied until it would be violated. C <= 0 uses the soft bias while pushing out and is rigid
// in the relax pass.
//
// solveMotorRow: drives the row's position x (rate Cdot), m_eff = 1 / k:
//   position target (hertz > 0): soft row on C = x - target (softness.hpp),
//     lambda = -mass_scale m_eff (Cdot + bias_rate C) - impulse_scale lambda_acc;
//   velocity target (hertz = 0): lambda = -m_eff (Cdot - target_velocity);
//   the accumulated impulse is clamped to +-max_torque h (a motor has finite strength);
//   viscous damping c (force -c Cdot), implicit over the substep: the soft row Cdot -> 0 with
//   gamma = 1 / (h c) and mu the damping impulse accumulated over the substep's sweeps (reset at
//   the warm start, never carried over),
//     lambda = -(Cdot + gamma mu) / (1/m_eff + gamma),  mu += lambda,
//   whose fixed point mu = -h c Cdot' (Cdot' the substep's final rate) is implicit Euler of the
//   damper. It is solved in every joint sweep, so the damper and the rows it couples with settle
//   together in any row order.
#pragma once

#include <algorithm>

#include "ragdoll_sim/joint.hpp"
#include "solver_context.hpp"

namespace ragdoll_sim {

struct AngularRow {
  Vec3 j;
  double k;
  AngularRow(const Vec3& j_, const SolverBody& A, const SolverBody& B)
      : j(j_), k(j_.dot((A.inv_inertia + B.inv_inertia) * j_)) {}
  AngularRow(const Vec3& j_, double k_) : j(j_), k(k_) {}  // k computed once per substep
  double rate(const SolverBody& A, const SolverBody& B) const { return j.dot(B.w - A.w); }
  void apply(SolverBody& A, SolverBody& B, double lambda) const {
    applyPairAngularImpulse(A, B, lambda * j);
  }
  AngularRow negated() const {
    AngularRow r = *this;
    r.j = -j;
    return r;
  }
};

struct LinearRow {
  Vec3 n, jA, jB;  // direction, angular parts lA x n and rB x n
  double k;
  LinearRow(const Vec3& n_, const Vec3& lA, const Vec3& rB, const SolverBody& A,
            const SolverBody& B)
      : n(n_), jA(lA.cross(n_)), jB(rB.cross(n_)) {
    k = A.inv_mass + B.inv_mass + jA.dot(A.inv_inertia * jA) + jB.dot(B.inv_inertia * jB);
  }
  double rate(const SolverBody& A, const SolverBody& B) const {
    return n.dot(B.v - A.v) + jB.dot(B.w) - jA.dot(A.w);
  }
  void apply(SolverBody& A, SolverBody& B, double lambda) const {
    A.v -= (A.inv_mass * lambda) * n;
    A.w -= A.inv_inertia * (lambda * jA);
    B.v += (B.inv_mass * lambda) * n;
    B.w += B.inv_inertia * (lambda * jB);
  }
  LinearRow negated() const {
    LinearRow r = *this;
    r.n = -n;
    r.jA = -jA;
    r.jB = -jB;
    return r;
  }
};

// Signed distance of x beyond [lower - slop, upper + slop]: > 0 above, < 0 below, 0 inside
// (the position projection of the limit parts).
inline double rangeExcess(double x, double lower, double upper, double slop) {
  if (x > upper + slop) return x - upper - slop;
  if (x < lower - slop) return x - lower + slop;
  return 0.0;
}

template <class Row>
void solveInequalityRow(SolverBody& A, SolverBody& B, const Row& row, double C, double& acc,
                        const StepContext& ctx, bool use_bias) {
  if (!(row.k > 1e-300)) return;
  const double rate = row.rate(A, B);
  // Speculative row that stays open with nothing accumulated: lambda <= 0 clamps to 0.
  if (C > 0.0 && acc == 0.0 && C + ctx.h * rate >= 0.0) return;
  double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
  if (C > 0.0) {
    bias = C * ctx.inv_h;
  } else if (use_bias) {
    bias = ctx.joint_softness.bias_rate * C;
    mass_scale = ctx.joint_softness.mass_scale;
    impulse_scale = ctx.joint_softness.impulse_scale;
  }
  double lambda = -mass_scale / row.k * (rate + bias) - impulse_scale * acc;
  const double next = std::max(acc + lambda, 0.0);
  lambda = next - acc;
  acc = next;
  row.apply(A, B, lambda);
}

template <class Row>
void solveMotorRow(SolverBody& A, SolverBody& B, const Row& row, double position,
                   const JointMotor& motor, double& acc, double& damping_acc,
                   const StepContext& ctx) {
  if (!(row.k > 1e-300)) return;
  if (motor.damping > 0.0) {
    const double gamma = 1.0 / (ctx.h * motor.damping);
    const double lambda = -(row.rate(A, B) + gamma * damping_acc) / (row.k + gamma);
    damping_acc += lambda;
    row.apply(A, B, lambda);
  }
  if (!motor.enabled) return;
  const double m = 1.0 / row.k, rate = row.rate(A, B);
  double lambda;
  if (motor.hertz > 0.0) {
    const Softness soft = Softness::make(motor.hertz, motor.damping_ratio, ctx.h);
    lambda = -soft.mass_scale * m * (rate + soft.bias_rate * (position - motor.target)) -
             soft.impulse_scale * acc;
  } else {
    lambda = -m * (rate - motor.target_velocity);
  }
  const double max_impulse = motor.max_torque * ctx.h;
  const double next = std::clamp(acc + lambda, -max_impulse, max_impulse);
  lambda = next - acc;
  acc = next;
  row.apply(A, B, lambda);
}

}  // namespace ragdoll_sim
