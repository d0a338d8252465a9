// Angle lock part: joint frame B keeps the orientation of joint frame A (3 angular rows).
//   q_err = qB qA^-1 (world rotation from frame A to frame B), sign-corrected to w >= 0 so the
//   error is the short way round;
//   C    = 2 vec(q_err)           (= the world rotation vector of the error to first order)
//   Cdot = wB - wA,  J = [0 -I 0 I]
//   K    = IA^-1 + IB^-1
//   lambda = -mass_scale K^-1 (Cdot + bias_rate C) - impulse_scale lambda_acc   (softness.hpp),
//   angular impulse lambda on B, minus on A (a pure couple: momentum and angular momentum kept).
// The frames are tracked through the substeps with the bodies' delta rotations.
// Position projection (after the substeps): the angular position impulse L = -K^-1 C' (C' = C
// less the slop, at most max_correction) turns the frames back together to first order.
#pragma once

#include <limits>

#include <Eigen/Dense>

#include "solver_context.hpp"

namespace ragdoll_sim {

struct AngleLockPart {
  Quat qa0 = Quat::Identity(), qb0 = Quat::Identity();  // world joint frames at step start
  Vec3 impulse = Vec3::Zero();

  void prepare(const Quat& frame_a_world, const Quat& frame_b_world) {
    qa0 = frame_a_world;
    qb0 = frame_b_world;
  }

  Vec3 error(const SolverBody& A, const SolverBody& B) const {
    Quat e = (B.dq * qb0) * (A.dq * qa0).conjugate();
    if (e.w() < 0.0) e.coeffs() = -e.coeffs();
    return 2.0 * e.vec();
  }

  void warmStart(SolverBody& A, SolverBody& B) const { applyPairAngularImpulse(A, B, impulse); }

  bool project(SolverBody& A, SolverBody& B, double slop, double max_correction) const {
    Vec3 C = error(A, B);
    if (!trimToSlop(C, slop, max_correction)) return false;
    const Mat3 K = A.inv_inertia + B.inv_inertia;
    applyPairAngularPositionImpulse(A, B, -(inverseOrZero(K) * C));
    return true;
  }

  // max_impulse caps the accumulated impulse's norm (a breakable weld's break_torque h); true
  // when it was reached.
  bool solve(SolverBody& A, SolverBody& B, const Softness& soft, bool use_bias,
             double max_impulse = std::numeric_limits<double>::infinity()) {
    const Softness s = soft.orRigid(use_bias);
    const Vec3 bias = use_bias ? Vec3(s.bias_rate * error(A, B)) : Vec3::Zero();
    const Mat3 K = A.inv_inertia + B.inv_inertia;
    if (!(K.trace() > 1e-300)) return false;  // both bodies static or asleep
    const Vec3 old = impulse;
    impulse += -s.mass_scale * K.ldlt().solve(B.w - A.w + bias) - s.impulse_scale * impulse;
    const double n = impulse.norm();
    const bool capped = n > max_impulse;
    if (capped) impulse *= max_impulse / n;
    applyPairAngularImpulse(A, B, impulse - old);
    return capped;
  }
};

}  // namespace ragdoll_sim
