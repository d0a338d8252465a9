// Joint angles from the relative rotation of the two joint frames, and their rate Jacobians.
// The hinge and Euler angles are computed by joint_angles_kernel.hpp (one joint or several at a
// time, the same bits); the derivations are here.
//
// Hinge: theta = signed angle about the axis a between a perpendicular u carried by frame A
// and the same u carried by frame B; theta_dot = a . (wB - wA). (The cheaper twist angle of
// q_rel about a, equal for a true hinge, differs on a bent one and lets ragdolls settle later.)
//
// Ball (Euler): R_rel = R(a0,t0) R(a1,t1) R(a2,t2) with orthonormal joint-frame axes. With
// P = [a0 a1 s a2] (s = +-1 so that det P = +1), R' = P^T R_rel P = Rx(t0) Ry(t1) Rz(s t2):
//   t1 = asin(R'02), t0 = atan2(-R'12, R'22), s t2 = atan2(-R'01, R'00).
// P is a rotation, so R' is the matrix of q' = qP^-1 q_rel qP: only the five entries above are
// formed from q' (no 3x3 products). Since R'12 = -s0 c1, R'22 = c0 c1 and R'02 = s1 with
// c1 = cos t1 >= 0: c1 = |(R'12, R'22)|, c0 = R'22 / c1, s0 = -R'12 / c1, s1 = R'02, so the
// rates below need no trigonometry.
// Rates: w' = t0_dot ex + t1_dot Rx(t0) ey + (s t2)_dot Rx(t0) Ry(t1) ez = M(t) t_dot, with
//   M = [ (1,0,0), (0,c0,s0), (s1,-s0 c1,c0 c1) ],  det M = cos t1 (gimbal lock at t1 = +-pi/2).
// So t_dot = diag(1,1,s) M^-1 P^T R_JA^T (wB - wA): each row is one limit's Jacobian. With
// Q = R_JA P = [q0 q1 q2] (the matrix of qA qP) and v = -s0 q1 + c0 q2, the rows are
//   j0 = q0 - (s1 / c1) v,  j1 = c0 q1 + s0 q2,  j2 = s v / c1.
//
// Ball (swing-twist): q_rel = qA^-1 qB = q_swing q_twist, q_twist about the twist axis t (joint
// frame), q_swing the shortest arc carrying t to q_rel t. With tA = qA t, tB = qB t (world):
//   swing = angle(tA, tB) in [0, pi];  d/dt(tA . tB) = -(wB - wA) . (tA x tB), so
//     swing_dot = (wB - wA) . s,  s = (tA x tB) / |tA x tB|  (undefined at swing = 0);
//   twist: q_rel.w = cos(swing/2) cos(twist/2), q_rel.vec . t = cos(swing/2) sin(twist/2), so
//     twist = 2 atan2(q_rel.vec . t, q_rel.w) wrapped to (-pi, pi];
//   the shortest arc's own angular velocity is perpendicular to t + b (b = q_swing t), so
//     twist_dot = (wB - wA) . (tA + tB) / (1 + tA . tB)  (undefined at swing = pi).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Dense>

#include "joint_angles_lanes.hpp"
#include "ragdoll_sim/math.hpp"

namespace ragdoll_sim {

// The frames of a joint between bodies A and B as the angle kernels take them: (dq_a q_a) frame_a
// and (dq_b q_b) frame_b; joint frames alone with the identity for the rest.
inline const double* identityQuat() {
  static const double q[4] = {0.0, 0.0, 0.0, 1.0};
  return q;
}
inline JointFrameInputs frameInputs(const Quat& dq_a, const Quat& q_a, const Quat& frame_a,
                                    const Quat& dq_b, const Quat& q_b, const Quat& frame_b) {
  return {dq_a.coeffs().data(), q_a.coeffs().data(), frame_a.coeffs().data(),
          dq_b.coeffs().data(), q_b.coeffs().data(), frame_b.coeffs().data()};
}
// Joint j's frames at its solver bodies' current deltas (JointBase, SolverBody, BodyMotion).
template <class Joint, class Body, class Motions>
JointFrameInputs currentFrames(const Joint& j, const Body& A, const Body& B, const Motions& m) {
  return frameInputs(A.dq, m[j.a].q, j.frame_a.q, B.dq, m[j.b].q, j.frame_b.q);
}
inline JointFrameInputs frameInputs(const Quat& frame_a, const Quat& frame_b) {
  return {identityQuat(), identityQuat(), frame_a.coeffs().data(),
          identityQuat(), identityQuat(), frame_b.coeffs().data()};
}

// The hinge angle about axis (joint frame; perp = anyPerpendicular(axis), which the solver
// keeps) and its row frame_a * axis (joint_angles_lanes.hpp).
inline double hingeAngle(const JointFrameInputs& in, const Vec3& axis, const Vec3& perp,
                         Vec3* row = nullptr) {
  Vec3 r;
  double angle;
  const HingeAngleJob job{in, axis.data(), perp.data(), r.data(), &angle};
  hingeAngles(&job, 1);
  if (row) *row = r;
  return angle;
}
inline double hingeAngle(const Quat& frame_a, const Quat& frame_b, const Vec3& axis) {
  return hingeAngle(frameInputs(frame_a, frame_b), axis, anyPerpendicular(axis));
}

struct EulerBasis {
  Quat qP = Quat::Identity();  // the rotation P = [a0 a1 s a2]
  double s = 1.0;

  explicit EulerBasis(const std::array<Vec3, 3>& axes = {Vec3::UnitX(), Vec3::UnitY(),
                                                         Vec3::UnitZ()}) {
    Mat3 P;
    P.col(0) = axes[0].normalized();
    P.col(1) = axes[1].normalized();
    P.col(2) = axes[2].normalized();
    if (P.determinant() < 0) {
      s = -1.0;
      P.col(2) = -P.col(2);
    }
    // The axes are orthonormal to ~1e-6 (the URDF loader's check); the nearest rotation.
    const Eigen::JacobiSVD<Mat3> svd(P, Eigen::ComputeFullU | Eigen::ComputeFullV);
    qP = Quat(Mat3(svd.matrixU() * svd.matrixV().transpose())).normalized();
  }

  // Angles (t0, t1, t2) of the relative rotation of the joint frames; with rows != nullptr also
  // their world Jacobian rows j_i (t_i dot = j_i . (wB - wA)), false near gimbal lock
  // (joint_angles_lanes.hpp).
  bool angles(const JointFrameInputs& in, Vec3& t, std::array<Vec3, 3>* rows = nullptr) const {
    static_assert(sizeof(std::array<Vec3, 3>) == 9 * sizeof(double), "the kernel's 9 doubles");
    std::array<Vec3, 3> r;
    double ok;
    const EulerAngleJob job{in, qP.coeffs().data(), &s, t.data(), r[0].data(), &ok};
    eulerAngles(&job, 1);
    if (!rows) return true;
    if (ok == 0.0) return false;
    *rows = r;
    return true;
  }
  bool angles(const Quat& frame_a, const Quat& frame_b, Vec3& t,
              std::array<Vec3, 3>* rows = nullptr) const {
    return angles(frameInputs(frame_a, frame_b), t, rows);
  }
  Vec3 angles(const Quat& frame_a, const Quat& frame_b) const {
    Vec3 t;
    angles(frame_a, frame_b, t);
    return t;
  }
};

struct SwingTwist {
  double swing = 0.0, twist = 0.0;
  Vec3 swing_row = Vec3::Zero(), twist_row = Vec3::Zero();  // world rate rows
  bool swing_valid = false, twist_valid = false;             // rows defined
};

// Swing-twist angles of frame_b relative to frame_a about the unit twist axis (joint frame).
inline SwingTwist swingTwist(const Quat& frame_a, const Quat& frame_b, const Vec3& axis) {
  SwingTwist r;
  const Vec3 tA = frame_a * axis, tB = frame_b * axis;
  const Vec3 c = tA.cross(tB);
  const double sn = c.norm(), cs = tA.dot(tB);
  r.swing = std::atan2(sn, cs);
  r.swing_valid = sn > 1e-9;
  if (r.swing_valid) r.swing_row = c / sn;
  const Quat q = frame_a.conjugate() * frame_b;
  const double tw = 2.0 * std::atan2(q.vec().dot(axis), q.w());  // (-2 pi, 2 pi]
  r.twist = tw > M_PI ? tw - 2.0 * M_PI : (tw <= -M_PI ? tw + 2.0 * M_PI : tw);
  r.twist_valid = 1.0 + cs > 1e-6;
  if (r.twist_valid) r.twist_row = (tA + tB) / (1.0 + cs);
  return r;
}

}  // namespace ragdoll_sim
