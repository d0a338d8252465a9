// Point constraint part: anchor A (fixed in body A) and anchor B (fixed in B) coincide.
//   C    = (xB + rB) - (xA + rA)                           3 rows, r = anchor - COM (world)
//   Cdot = vB + wB x rB - vA - wA x rA
//   J    = [ -I  skew(rA)  I  -skew(rB) ]
//   K    = J M^-1 J^T = (1/mA + 1/mB) I - skew(rA) IA^-1 skew(rA) - skew(rB) IB^-1 skew(rB)
//   lambda = -mass_scale K^-1 (Cdot + bias_rate C) - impulse_scale lambda_acc   (softness.hpp)
// Position projection (after the substeps, SolverSettings::position_iterations): P = -K^-1 C' with
// C' = C (1 - slop / |C|) moves and turns the bodies so that |C| -> slop to first order, leaving
// the velocities alone (no energy is added, unlike a velocity bias). The slop (joint_slop) is
// left to the soft rows, which friction can resist: it keeps the projection off resting limbs.
// C is tracked through the substeps from the bodies' accumulated deltas: the anchors are
// rotated by the delta rotation and the centres moved by the delta positions. K^-1 is formed
// once per substep (at the warm start) from the current anchors: a stale K from the step start
// over-corrects once a body spins a good part of a radian per step, and Gauss-Seidel diverges.
// The rotated anchors rA, rB only change when the positions do, so they are computed once per
// position state (refresh: at the first substep's warm start and after each position update)
// and read by every sweep.
// -skew(r) I skew(r) = S^T I S (S = skew(r), S^T = -S) is formed entry by entry:
// (S^T I S)_ij = c_i . I c_j with c_j = r x e_j, which has a zero; symmetric, ~30 products
// instead of the ~110 of two 3x3 products, since K is formed every substep for every joint.
#pragma once

#include <algorithm>
#include <limits>

#include "solver_context.hpp"

namespace ragdoll_sim {

// S^T I S for S = skew(r) and a symmetric I (see the top of the file).
inline Mat3 crossInertia(const Vec3& r, const Mat3& I) {
  const double x = r.x(), y = r.y(), z = r.z();
  const Vec3 I0 = z * I.col(1) - y * I.col(2);   // I c_0, c_0 = (0, z, -y)
  const Vec3 I1 = x * I.col(2) - z * I.col(0);   // I c_1, c_1 = (-z, 0, x)
  const Vec3 I2 = y * I.col(0) - x * I.col(1);   // I c_2, c_2 = (y, -x, 0)
  Mat3 M;
  M(0, 0) = z * I0.y() - y * I0.z();
  M(1, 1) = x * I1.z() - z * I1.x();
  M(2, 2) = y * I2.x() - x * I2.y();
  M(0, 1) = M(1, 0) = z * I1.y() - y * I1.z();
  M(0, 2) = M(2, 0) = z * I2.y() - y * I2.z();
  M(1, 2) = M(2, 1) = x * I2.z() - z * I2.x();
  return M;
}

// (1/mA + 1/mB + gamma) I3 + S_A^T IA^-1 S_A + S_B^T IB^-1 S_B.
inline Mat3 pointMass(const SolverBody& A, const SolverBody& B, const Vec3& rA, const Vec3& rB,
                      double gamma) {
  Mat3 K = crossInertia(rA, A.inv_inertia) + crossInertia(rB, B.inv_inertia);
  K.diagonal().array() += A.inv_mass + B.inv_mass + gamma;
  return K;
}

struct PointPart {
  Vec3 rA0 = Vec3::Zero(), rB0 = Vec3::Zero();  // world anchors from the COMs at step start
  Vec3 delta_center = Vec3::Zero();             // xB - xA at step start
  Vec3 rA = Vec3::Zero(), rB = Vec3::Zero();    // anchors at the current dq (refresh)
  Vec3 impulse = Vec3::Zero();                  // accumulated (per substep)
  Mat3 k_inv = Mat3::Zero();                    // (K + gamma I)^-1, gamma = 0 when rigid

  void prepare(const BodyMotion& A, const BodyMotion& B, const Vec3& local_anchor_a,
               const Vec3& local_anchor_b) {
    rA0 = A.q * (local_anchor_a - A.local_com);
    rB0 = B.q * (local_anchor_b - B.local_com);
    delta_center = centerOffset(A, B);
  }

  void refresh(const SolverBody& A, const SolverBody& B) {
    rA = A.dq * rA0;
    rB = B.dq * rB0;
  }

  // C at anchors rA, rB (world, from the COMs at the current deltas).
  Vec3 errorAt(const SolverBody& A, const SolverBody& B, const Vec3& rA, const Vec3& rB) const {
    return (B.dp - A.dp) + (rB - rA) + delta_center;
  }
  // C at the refreshed anchors.
  Vec3 error(const SolverBody& A, const SolverBody& B) const { return errorAt(A, B, rA, rB); }

  // Forms K^-1 at the anchors, refreshed first unless they are current (the deltas have not
  // moved since the last refresh); gamma > 0 softens K for a spring.
  void updateMass(const SolverBody& A, const SolverBody& B, double gamma, bool anchors_current) {
    if (!anchors_current) refresh(A, B);
    k_inv = inverseOrZero(pointMass(A, B, rA, rB, gamma));
  }

  void warmStart(SolverBody& A, SolverBody& B) const { applyPairImpulse(A, B, impulse, rA, rB); }

  // Hooke spring F = -k x - c v between the anchors instead of the rigid row, implicit over
  // the substep (Catto's soft constraints): gamma = 1 / (h (c + h k)), beta = k / (c + h k),
  //   lambda = -(K + gamma I)^-1 (Cdot + beta C);  for one body on a fixed anchor this is
  // exactly implicit Euler of m x'' = -k x - c x'. Returns the spring force k |C|.
  double solveSpring(SolverBody& A, SolverBody& B, double k, double c, double h) {
    const Vec3 C = error(A, B);
    const Vec3 cdot = B.v + B.w.cross(rB) - A.v - A.w.cross(rA);
    const double beta = k / (c + h * k);  // gamma went into k_inv (springGamma)
    const Vec3 lambda = -(k_inv * (cdot + beta * C));
    applyPairImpulse(A, B, lambda, rA, rB);
    return k * C.norm();
  }

  // K from the current anchors (a fast spin turns them far within one step, and a stale K
  // overshoots). Only the error beyond `slop` is removed (SolverSettings::joint_slop), and at most
  // max_correction of it per sweep.
  bool project(SolverBody& A, SolverBody& B, double max_correction, double slop) const {
    const Vec3 rA = A.dq * rA0, rB = B.dq * rB0;
    Vec3 C = errorAt(A, B, rA, rB);
    if (!trimToSlop(C, slop, max_correction)) return false;
    const Mat3 k_inv = inverseOrZero(pointMass(A, B, rA, rB, 0.0));
    if (k_inv.isZero(0.0)) return false;
    applyPairPositionImpulse(A, B, -(k_inv * C), rA, rB);
    return true;
  }

  static double springGamma(double k, double c, double h) { return 1.0 / (h * (c + h * k)); }

  // max_impulse caps |accumulated impulse| (a breakable joint transmits at most its
  // strength); returns true when the cap was reached.
  bool solve(SolverBody& A, SolverBody& B, const Softness& soft, bool use_bias,
             double max_impulse = std::numeric_limits<double>::infinity()) {
    const Vec3 cdot = B.v + B.w.cross(rB) - A.v - A.w.cross(rA);
    const Softness s = soft.orRigid(use_bias);
    const Vec3 bias = use_bias ? Vec3(s.bias_rate * error(A, B)) : Vec3::Zero();
    Vec3 next = impulse - s.mass_scale * (k_inv * (cdot + bias)) - s.impulse_scale * impulse;
    bool saturated = false;
    if (max_impulse < std::numeric_limits<double>::infinity()) {  // unbreakable: no square root
      const double n = next.norm();
      saturated = n > max_impulse;
      if (saturated) next *= max_impulse / n;
    }
    applyPairImpulse(A, B, next - impulse, rA, rB);
    impulse = next;
    return saturated;
  }
};

}  // namespace ragdoll_sim
