// The joint angles of joint_angles_lanes.hpp written once for a lane type D: double, Double2 or
// Double4 (double_lanes.hpp). Selects take both sides (a vector computes them anyway), so every
// width does the same operations; no fused multiply-add (the files are built with
// -ffp-contract=off).
//
// atan2(y, x): with t = min(|x|, |y|) / max(|x|, |y|) in [0, 1],
//   atan t = Cephes' atan: t + t z P(z) / Q(z), z = t^2, for t <= 0.66, and above it
//   pi/4 + atan((t - 1) / (t + 1)), the argument in (-0.21, 0] (one division either way);
// then pi/2 - a where |y| > |x|, pi - a where x < 0 (its sign bit: atan2(+-0, -0) = +-pi), and
// y's sign. The low parts of pi/4, pi/2 and pi go in last: within 2 ulp of the correctly rounded
// result (test_joint_angles_lanes.cpp). asin s = atan2(s, sqrt((1 - s)(1 + s))).
// The angles and rows: joint_angles.hpp's formulas, q v as Eigen's _transformVector,
// a . b = a0 b0 + (a1 b1 + a2 b2), c1 = sqrt(r12^2 + r22^2) and its reciprocal once.
// As double_lanes.hpp: no std headers or Eigen, and an inline namespace per instruction set.
#pragma once

#include "double_lanes.hpp"
#include "joint_angles_lanes.hpp"

#if defined(__AVX2__)
#define RAGDOLL_SIM_ANGLES_ISA joint_angles_avx2
#else
#define RAGDOLL_SIM_ANGLES_ISA joint_angles_sse2
#endif

namespace ragdoll_sim {
namespace joint_angles {
inline namespace RAGDOLL_SIM_ANGLES_ISA {

using double_lanes::cross;
using double_lanes::dot;
using double_lanes::gather;
using double_lanes::magnitude;
using double_lanes::quatProduct;
using double_lanes::rotate;
using double_lanes::rotationMatrix;
using double_lanes::scatter;
using double_lanes::signBit;
using double_lanes::squareRoot;

// atan(num / den) for 0 <= num <= den, den > 0: above 0.66, atan((num - den) / (num + den)) +
// pi/4 (num - den exact), so that one division forms the argument.
template <class D>
inline D atanUnit(D num, D den) {
  constexpr double P0 = -0.8750608600031904, P1 = -16.157537187333652, P2 = -75.00855792314705,
                   P3 = -122.88666844901361, P4 = -64.85021904942025;
  constexpr double Q0 = 24.858464901423062, Q1 = 165.02700983169885, Q2 = 432.88106049129027,
                   Q3 = 485.3903996359137, Q4 = 194.5506571482614;
  constexpr double kPio4 = 0.7853981633974483, kPio4Low = 3.061616997868383e-17;
  const D zero = D() + 0.0;
  const auto big = num > 0.66 * den;
  const D x = (big ? num - den : num) / (big ? num + den : den);
  const D z = x * x;
  const D p = (((P0 * z + P1) * z + P2) * z + P3) * z + P4;
  const D q = ((((z + Q0) * z + Q1) * z + Q2) * z + Q3) * z + Q4;
  return (big ? zero + kPio4 : zero) + ((x * (z * p / q) + (big ? zero + kPio4Low : zero)) + x);
}

template <class D>
inline D atan2Lanes(D y, D x) {
  constexpr double kPio2 = 1.5707963267948966, kPio2Low = 6.123233995736766e-17;
  constexpr double kPi = 3.141592653589793, kPiLow = 1.2246467991473532e-16;
  const D zero = D() + 0.0, one = D() + 1.0;
  const D ax = magnitude(x), ay = magnitude(y);
  const auto swap = ax < ay;
  const D num = swap ? ax : ay, den = swap ? ay : ax;
  // atan2(+-0, +-0): atan(0 / 1), then 0 or pi
  const auto zeros = den > zero;
  D a = atanUnit(zeros ? num : zero, zeros ? den : one);
  a = swap ? (kPio2 - a) + kPio2Low : a;
  a = signBit(x) ? (kPi - a) + kPiLow : a;
  a = signBit(y) ? -a : a;
  return x == x ? (y == y ? a : y) : x;  // NaN in, NaN out
}

template <class D>
inline D asinLanes(D s) {
  return atan2Lanes(s, squareRoot((1.0 - s) * (1.0 + s)));
}

template <class D>
inline void conjugate(const D q[4], D out[4]) {
  for (int j = 0; j < 3; ++j) out[j] = -q[j];
  out[3] = q[3];
}
// The joint frames fa, fb of jobs[0, W).
template <class D, int W, class Job>
inline void jointFrames(const Job* jobs, D fa[4], D fb[4]) {
  const double *dqa[W], *qa[W], *la[W], *dqb[W], *qb[W], *lb[W];
  for (int l = 0; l < W; ++l) {
    const JointFrameInputs& in = jobs[l].in;
    dqa[l] = in.dq_a, qa[l] = in.q_a, la[l] = in.frame_a;
    dqb[l] = in.dq_b, qb[l] = in.q_b, lb[l] = in.frame_b;
  }
  D dq[4], q[4], l4[4], t[4];
  gather<4>(dqa, dq);
  gather<4>(qa, q);
  gather<4>(la, l4);
  quatProduct(dq, q, t);
  quatProduct(t, l4, fa);
  gather<4>(dqb, dq);
  gather<4>(qb, q);
  gather<4>(lb, l4);
  quatProduct(dq, q, t);
  quatProduct(t, l4, fb);
}

// jobs[0, W), one overload per kind of job.
template <class D>
inline void jobLanes(const HingeAngleJob* jobs) {
  constexpr int W = sizeof(D) / sizeof(double);
  const double *axis[W], *perp[W];
  double *row_out[W], *angle_out[W];
  for (int l = 0; l < W; ++l) {
    axis[l] = jobs[l].axis, perp[l] = jobs[l].perp;
    row_out[l] = jobs[l].row, angle_out[l] = jobs[l].angle;
  }
  D fa[4], fb[4], a[3], u[3], row[3], ua[3], ub[3], n[3];
  jointFrames<D, W>(jobs, fa, fb);
  gather<3>(axis, a);
  gather<3>(perp, u);
  rotate(fa, a, row);
  rotate(fa, u, ua);
  rotate(fb, u, ub);
  cross(ua, ub, n);
  const D angle[1] = {atan2Lanes(dot(row, n), dot(ua, ub))};
  scatter<3>(row, row_out);
  scatter<1>(angle, angle_out);
}

template <class D>
inline void jobLanes(const EulerAngleJob* jobs) {
  constexpr int W = sizeof(D) / sizeof(double);
  const double *basis[W], *sign[W];
  double *angles_out[W], *rows_out[W], *ok_out[W];
  for (int l = 0; l < W; ++l) {
    basis[l] = jobs[l].basis, sign[l] = jobs[l].sign;
    angles_out[l] = jobs[l].angles, rows_out[l] = jobs[l].rows, ok_out[l] = jobs[l].ok;
  }
  D fa[4], fb[4], qp[4], s[1], c[4], rel[4], t[4], q[4];
  jointFrames<D, W>(jobs, fa, fb);
  gather<4>(basis, qp);
  gather<1>(sign, s);
  // q = qP^-1 (fa^-1 fb) qP
  conjugate(fa, c);
  quatProduct(c, fb, rel);
  conjugate(qp, c);
  quatProduct(c, rel, t);
  quatProduct(t, qp, q);
  const D x = q[0], y = q[1], z = q[2], w = q[3];
  const D one = D() + 1.0, minus_one = D() - 1.0;
  const D r00 = 1.0 - 2.0 * (y * y + z * z), r01 = 2.0 * (x * y - w * z);
  D r02 = 2.0 * (x * z + w * y);
  r02 = r02 < minus_one ? minus_one : (one < r02 ? one : r02);  // std::clamp
  const D r12 = 2.0 * (y * z - w * x), r22 = 1.0 - 2.0 * (x * x + y * y);
  const D angles[3] = {atan2Lanes(-r12, r22), asinLanes(r02), s[0] * atan2Lanes(-r01, r00)};
  scatter<3>(angles, angles_out);
  const D c1 = squareRoot(r12 * r12 + r22 * r22);
  const D ok[1] = {c1 < D() + 1e-3 ? D() + 0.0 : one};
  scatter<1>(ok, ok_out);
  const D inv_c1 = one / c1;
  const D c0 = r22 * inv_c1, s0 = -r12 * inv_c1, s1 = r02;
  // Q = the matrix of fa qP (column-major: its columns q0, q1, q2)
  D g[4], Q[9];
  quatProduct(fa, qp, g);
  rotationMatrix(g, Q);
  const D *q0 = Q, *q1 = Q + 3, *q2 = Q + 6;
  const D k0 = s1 * inv_c1, k2 = s[0] * inv_c1;
  D rows[9];
  for (int j = 0; j < 3; ++j) {
    const D v = c0 * q2[j] - s0 * q1[j];
    rows[j] = q0[j] - k0 * v;
    rows[3 + j] = c0 * q1[j] + s0 * q2[j];
    rows[6 + j] = k2 * v;
  }
  // near gimbal lock the rows are left as they were
  for (int l = 0; l < W; ++l)
    if (*ok_out[l] != 0.0)
      for (int j = 0; j < 9; ++j) rows_out[l][j] = double_lanes::lane(rows[j], l);
}

// jobs[0, count) W at a time; count is a multiple of W (byLaneWidth).
template <class D, class Job>
inline void jobBlocks(const Job* jobs, int count) {
  constexpr int W = sizeof(D) / sizeof(double);
  for (int k = 0; k + W <= count; k += W) jobLanes<D>(jobs + k);
}

}  // namespace RAGDOLL_SIM_ANGLES_ISA
}  // namespace joint_angles
}  // namespace ragdoll_sim
