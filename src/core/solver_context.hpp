// What every constraint needs during one step.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "body.hpp"
#include "ragdoll_sim/world.hpp"
#include "softness.hpp"

namespace ragdoll_sim {

struct StepContext {
  double dt = 0.0;        // full step
  double h = 0.0;         // substep
  double inv_h = 0.0;
  int substeps = 1;       // h = dt / substeps
  int relax = 0;          // contact relax sweeps per substep (the first joint_relax_iterations also relax the joints)
  bool track_impulses = false;  // World::setContactImpulseTracking
  int lanes = 1;          // SolverSettings::lanes resolved: 1 (double rows), 4 or 8
  bool odd_step = false;  // the World's steps so far are odd in number (contact_wide.hpp)
  Softness contact_softness;
  Softness joint_softness;
  const SolverSettings* settings = nullptr;
  // The solver bodies and their rotations by body index: the World's, or on a team thread
  // after the first that thread's own copy, or a split island's boundary array
  // (SolveData::team_bodies, split_bodies).
  std::vector<SolverBody>* bodies = nullptr;
  std::vector<Mat3>* rotations = nullptr;
  const std::vector<BodyMotion>* motions = nullptr;  // poses at the start of the step
};

// False for an identity solver body (static or asleep): nothing can move it, and the ground,
// shared by all islands, must not be written by two threads at once. The inverse inertia is
// positive semidefinite (R I^-1 R^T), so its diagonal alone tells whether it is zero (Eigen's
// isZero, to 1e-12), which keeps this test cheap on every contact row.
inline bool movable(const SolverBody& b) {
  constexpr double kZero = 1e-12;  // Eigen's dummy_precision<double>, as isZero() used
  return b.inv_mass > 0.0 || std::abs(b.inv_inertia(0, 0)) > kZero ||
         std::abs(b.inv_inertia(1, 1)) > kZero || std::abs(b.inv_inertia(2, 2)) > kZero;
}

// Whether b has not turned in the step (a static or sleeping body, or any at the step start):
// its delta turns nothing, so a vector it would turn is used as it is (the same value; only a
// -0 component could come back as +0).
inline bool unturned(const SolverBody& b) {
  return b.dq.w() == 1.0 && b.dq.x() == 0.0 && b.dq.y() == 0.0 && b.dq.z() == 0.0;
}

// Accumulated impulses are per substep (about force x h), so warm starting on substep h from
// impulses accumulated over h0 scales them by h / h0 (1 when h0 == h, exactly; h0 = 0: none
// kept yet); an island that changes its substep count thus starts with the impulse that holds it.
inline double warmStartScale(double h0, double h) { return h0 > 0.0 ? h / h0 : 1.0; }

// K^-1 of an effective mass matrix (2x2, 3x3), or zero where K is singular (det <= 1e-300).
// One cofactor pass gives both the inverse and the determinant.
template <class M>
M inverseOrZero(const M& K) {
  M inv;
  typename M::Scalar det;
  bool invertible;
  K.computeInverseAndDetWithCheck(inv, det, invertible, 1e-300);
  return invertible && det > 0.0 ? inv : M(M::Zero());
}

// Position projection of a vector error C (a point, a line, a rotation): only the part beyond
// `slop` is removed, at most max_correction of it per sweep. False when |C| <= slop.
template <class V>
bool trimToSlop(V& C, double slop, double max_correction) {
  const double n = C.norm();
  if (!(n > slop)) return false;
  C *= std::min(n - slop, max_correction) / n;
  return true;
}

// Applies a world impulse P at world offset r (from the COM) to A (negative) and B (positive).
// This and applyPairAngularImpulse are forced inline because GCC leaves them as calls in the
// joint parts, the solver's innermost loop.
[[gnu::always_inline]] inline void applyPairImpulse(SolverBody& A, SolverBody& B, const Vec3& P,
                                                    const Vec3& rA, const Vec3& rB) {
  if (movable(A)) {
    A.v -= A.inv_mass * P;
    A.w -= A.inv_inertia * rA.cross(P);
  }
  if (movable(B)) {
    B.v += B.inv_mass * P;
    B.w += B.inv_inertia * rB.cross(P);
  }
}

// Position-level "impulse" (a displacement times mass): moves the centres and turns the
// rotations instead of changing velocities (non-linear Gauss-Seidel, position_iterations).
inline void rotateDelta(SolverBody& b, const Vec3& theta) {
  Quat dq = b.dq;
  dq.coeffs() += 0.5 * (Quat(0, theta.x(), theta.y(), theta.z()) * b.dq).coeffs();
  b.dq = dq.normalized();
}
inline void applyPairPositionImpulse(SolverBody& A, SolverBody& B, const Vec3& P,
                                     const Vec3& rA, const Vec3& rB) {
  if (movable(A)) {
    A.dp -= A.inv_mass * P;
    rotateDelta(A, -(A.inv_inertia * rA.cross(P)));
  }
  if (movable(B)) {
    B.dp += B.inv_mass * P;
    rotateDelta(B, B.inv_inertia * rB.cross(P));
  }
}

// Position sweeps (numbered from 1 in a step): a projection that moved nothing when it last
// looked (its own mark is older than the last sweep) and whose bodies nothing has moved since
// (theirs too) would see the same poses again and move nothing: it is skipped. A move marks
// the projection and its movable bodies (never a static or sleeping one: those are shared by
// the islands). Marks from an earlier step only make a look happen.
inline bool unchangedSince(int sweep, int own_mark, const SolverBody& A, const SolverBody& B) {
  const int last = sweep - 1;
  return sweep > 1 && own_mark < last && A.moved_sweep < last && B.moved_sweep < last;
}
inline void markMoved(int sweep, int& own_mark, SolverBody& A, SolverBody& B) {
  own_mark = sweep;
  if (movable(A)) A.moved_sweep = sweep;
  if (movable(B)) B.moved_sweep = sweep;
}

// Angular position "impulse" L: turns A by -IA^-1 L and B by +IB^-1 L (no velocity change).
inline void applyPairAngularPositionImpulse(SolverBody& A, SolverBody& B, const Vec3& L) {
  if (movable(A)) rotateDelta(A, -(A.inv_inertia * L));
  if (movable(B)) rotateDelta(B, B.inv_inertia * L);
}

// Applies an angular impulse L to A (negative) and B (positive).
[[gnu::always_inline]] inline void applyPairAngularImpulse(SolverBody& A, SolverBody& B,
                                                           const Vec3& L) {
  if (movable(A)) A.w -= A.inv_inertia * L;
  if (movable(B)) B.w += B.inv_inertia * L;
}

}  // namespace ragdoll_sim
