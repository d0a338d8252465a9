// Hinge axis part: the hinge axis a1 fixed in A stays parallel to the axis a2 fixed in B.
// With b2, c2 unit vectors fixed in B and perpendicular to a2:
//   C    = [a1 . b2, a1 . c2]                                      2 rows
//   Cdot = U^T (wB - wA),  U = [b2 x a1, c2 x a1]   (d/dt(a1.b2) = (wB - wA) . (b2 x a1))
//   K    = U^T (IA^-1 + IB^-1) U                                   2x2
//   lambda = -mass_scale K^-1 (Cdot + bias_rate C) - impulse_scale lambda_acc,
//   angular impulse U lambda on B, minus on A. K^-1 is formed once per substep (updateMass).
// U and C change only with the positions: refresh() forms them at the first substep's warm
// start and after each position update, and every sweep in between reads them.
// Position projection (after the substeps): C beyond the slop (at most max_correction) is
// turned back by the angular position impulse U lambda, lambda = -K^-1 C'; no velocity added.
#pragma once

#include <Eigen/Dense>

#include "solver_context.hpp"

namespace ragdoll_sim {

struct HingeAxisPart {
  Vec3 a1_0 = Vec3::UnitZ(), a2_0 = Vec3::UnitZ();  // world at step start
  Vec3 b2_0 = Vec3::UnitX(), c2_0 = Vec3::UnitY();
  Vec3 u1 = Vec3::Zero(), u2 = Vec3::Zero();  // U's columns at the current dq (refresh)
  Eigen::Vector2d C = Eigen::Vector2d::Zero();
  Eigen::Vector2d impulse = Eigen::Vector2d::Zero();
  Eigen::Matrix2d k_inv = Eigen::Matrix2d::Zero();

  // Axes given in each body's axes (link frame).
  void prepare(const BodyMotion& A, const BodyMotion& B, const Vec3& axis_in_a,
               const Vec3& axis_in_b) {
    a1_0 = A.q * axis_in_a;
    a2_0 = B.q * axis_in_b;
    b2_0 = anyPerpendicular(a2_0);
    c2_0 = a2_0.cross(b2_0);
  }

  // U's columns and C at the bodies' current deltas.
  void at(const SolverBody& A, const SolverBody& B, Vec3& v1, Vec3& v2, Eigen::Vector2d& c) const {
    const Vec3 a1 = A.dq * a1_0;
    const Vec3 b2 = B.dq * b2_0, c2 = B.dq * c2_0;
    v1 = b2.cross(a1);
    v2 = c2.cross(a1);
    c = {a1.dot(b2), a1.dot(c2)};
  }

  void refresh(const SolverBody& A, const SolverBody& B) { at(A, B, u1, u2, C); }

  // Forms K^-1 at U, refreshed first (with C) unless current (the deltas have not moved since).
  void updateMass(const SolverBody& A, const SolverBody& B, bool axes_current) {
    if (!axes_current) refresh(A, B);
    k_inv = inverseOrZero(mass(A, B, u1, u2));
  }

  static Eigen::Matrix2d mass(const SolverBody& A, const SolverBody& B, const Vec3& u1,
                              const Vec3& u2) {
    const Mat3 I = A.inv_inertia + B.inv_inertia;
    const Vec3 Iu1 = I * u1, Iu2 = I * u2;
    Eigen::Matrix2d K;
    K << u1.dot(Iu1), u1.dot(Iu2), u2.dot(Iu1), u2.dot(Iu2);
    return K;
  }

  // At the current deltas (refresh's state is left to the velocity sweeps).
  bool project(SolverBody& A, SolverBody& B, double slop, double max_correction) const {
    Vec3 v1, v2;
    Eigen::Vector2d c;
    at(A, B, v1, v2, c);
    if (!trimToSlop(c, slop, max_correction)) return false;
    const Eigen::Vector2d l = -(inverseOrZero(mass(A, B, v1, v2)) * c);
    applyPairAngularPositionImpulse(A, B, l.x() * v1 + l.y() * v2);
    return true;
  }

  void warmStart(SolverBody& A, SolverBody& B) const {
    applyPairAngularImpulse(A, B, impulse.x() * u1 + impulse.y() * u2);
  }

  void solve(SolverBody& A, SolverBody& B, const Softness& soft, bool use_bias) {
    const Vec3 dw = B.w - A.w;
    const Eigen::Vector2d cdot(u1.dot(dw), u2.dot(dw));
    const Softness s = soft.orRigid(use_bias);
    const Eigen::Vector2d bias =
        use_bias ? Eigen::Vector2d(s.bias_rate * C) : Eigen::Vector2d::Zero();
    const Eigen::Vector2d lambda =
        -s.mass_scale * (k_inv * (cdot + bias)) - s.impulse_scale * impulse;
    impulse += lambda;
    applyPairAngularImpulse(A, B, lambda.x() * u1 + lambda.y() * u2);
  }
};

}  // namespace ragdoll_sim
