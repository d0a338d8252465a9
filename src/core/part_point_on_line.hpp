// Point-on-line part: anchor B stays on the line through anchor A along the axis (2 rows).
// With the slider geometry of part_slider_frame.hpp (lever arms lA = rA + d and rB):
//   C    = [n1 . d, n2 . d]
//   J_i  = [ -n_i  -(lA x n_i)  n_i  rB x n_i ]
//   K_ij = (1/mA + 1/mB) n_i . n_j + (lA x n_i)^T IA^-1 (lA x n_j) + (rB x n_i)^T IB^-1 (rB x n_j)
//   lambda = -mass_scale K^-1 (Cdot + bias_rate C) - impulse_scale lambda_acc   (softness.hpp);
//   the force lambda_1 n1 + lambda_2 n2 acts at pB on B, minus on A.
// max_impulse caps |accumulated impulse| (a breakable joint transmits at most its strength).
// Position projection (after the substeps): P = -K^-1 C' with C' = C (1 - slop / |C|) moves B's
// anchor back towards the line (joint_slop left, as in part_point.hpp); no velocity is added.
#pragma once

#include <limits>

#include <Eigen/Dense>

#include "part_slider_frame.hpp"

namespace ragdoll_sim {

struct PointOnLinePart {
  Eigen::Vector2d impulse = Eigen::Vector2d::Zero();

  Vec3 force(const SliderPose& p) const { return impulse.x() * p.n1 + impulse.y() * p.n2; }

  void warmStart(SolverBody& A, SolverBody& B, const SliderPose& p) const {
    applyPairImpulse(A, B, force(p), p.leverA(), p.rB);
  }

  // K for the angular parts a_i = lA x n_i, b_i = rB x n_i.
  static Eigen::Matrix2d mass(const SolverBody& A, const SolverBody& B, const Vec3& a1,
                              const Vec3& a2, const Vec3& b1, const Vec3& b2) {
    const double im = A.inv_mass + B.inv_mass;
    const Vec3 Ia1 = A.inv_inertia * a1, Ia2 = A.inv_inertia * a2;
    const Vec3 Ib1 = B.inv_inertia * b1, Ib2 = B.inv_inertia * b2;
    Eigen::Matrix2d K;
    K(0, 0) = im + a1.dot(Ia1) + b1.dot(Ib1);
    K(0, 1) = K(1, 0) = a1.dot(Ia2) + b1.dot(Ib2);
    K(1, 1) = im + a2.dot(Ia2) + b2.dot(Ib2);
    return K;
  }

  bool project(SolverBody& A, SolverBody& B, const SliderPose& p, double slop,
               double max_correction) const {
    Eigen::Vector2d C(p.n1.dot(p.d), p.n2.dot(p.d));
    if (!trimToSlop(C, slop, max_correction)) return false;
    const Vec3 lA = p.leverA();
    const Eigen::Matrix2d K =
        mass(A, B, lA.cross(p.n1), lA.cross(p.n2), p.rB.cross(p.n1), p.rB.cross(p.n2));
    const Eigen::Vector2d l = -(inverseOrZero(K) * C);
    applyPairPositionImpulse(A, B, l.x() * p.n1 + l.y() * p.n2, lA, p.rB);
    return true;
  }

  // Returns true when the cap was reached.
  bool solve(SolverBody& A, SolverBody& B, const SliderPose& p, const Softness& soft,
             bool use_bias, double max_impulse = std::numeric_limits<double>::infinity()) {
    const Vec3 lA = p.leverA();
    const Vec3 a1 = lA.cross(p.n1), a2 = lA.cross(p.n2);
    const Vec3 b1 = p.rB.cross(p.n1), b2 = p.rB.cross(p.n2);
    const Vec3 dv = B.v - A.v;
    const Eigen::Vector2d cdot(p.n1.dot(dv) + b1.dot(B.w) - a1.dot(A.w),
                               p.n2.dot(dv) + b2.dot(B.w) - a2.dot(A.w));
    const Softness s = soft.orRigid(use_bias);
    const Eigen::Vector2d bias =
        use_bias ? Eigen::Vector2d(s.bias_rate * Eigen::Vector2d(p.n1.dot(p.d), p.n2.dot(p.d)))
                 : Eigen::Vector2d::Zero();
    const Eigen::Matrix2d K = mass(A, B, a1, a2, b1, b2);
    if (!(K.determinant() > 1e-300)) return false;
    Eigen::Vector2d next =
        impulse - s.mass_scale * K.inverse() * (cdot + bias) - s.impulse_scale * impulse;
    const double n = next.norm();
    const bool saturated = n > max_impulse;
    if (saturated) next *= max_impulse / n;
    const Eigen::Vector2d lambda = next - impulse;
    impulse = next;
    applyPairImpulse(A, B, lambda.x() * p.n1 + lambda.y() * p.n2, lA, p.rB);
    return saturated;
  }
};

}  // namespace ragdoll_sim
