// refreshPointFrames (point_frames.hpp) written once for a lane type D, Double2 or Double4
// (double_lanes.hpp). Each lane does exactly the IEEE operations, in the order, of the Eigen
// expressions it replaces (EIGEN_DONT_VECTORIZE: Eigen's scalar paths; no fused multiply-add),
// so its bits are those of
//   rA = dqA rA0,  rB = dqB rB0,  C = (dpB - dpA) + (rB - rA) + center       (part_point.hpp)
//   a1 = dqA a1_0, b2 = dqB b2_0, c2 = dqB c2_0,  u1 = b2 x a1,  u2 = c2 x a1,
//   C_axis = (a1 . b2, a1 . c2)                                          (part_hinge_axis.hpp)
//   theta += h (j . (wB - wA)),  C_lower = min(theta - lower, kFarOpen),
//   C_upper = min(upper - theta, kFarOpen), both 1 for a row without a limit
//                                       (AngleAxes::advance; putAngleErrors of point_lanes.cpp)
// with q v Eigen's _transformVector: uv = q.vec x v, uv = uv + uv, then (v + q.w uv) + q.vec x uv;
// a x b componentwise a1 b2 - a2 b1, ...; a . b = a0 b0 + (a1 b1 + a2 b2) (Eigen's unrolled
// reduction halves the range). Quaternions are stored x, y, z, w.
// As double_lanes.hpp: no std headers or Eigen, and an inline namespace per instruction set.
#pragma once

#include "double_lanes.hpp"
#include "point_frames.hpp"

#if defined(__AVX2__)
#define RAGDOLL_SIM_FRAMES_ISA point_frames_avx2
#else
#define RAGDOLL_SIM_FRAMES_ISA point_frames_sse2
#endif

namespace ragdoll_sim {
namespace point_frames {
inline namespace RAGDOLL_SIM_FRAMES_ISA {

using double_lanes::cross;
using double_lanes::dot;
using double_lanes::gather;
using double_lanes::lane;
using double_lanes::rotate;
using double_lanes::storeFloats;

template <class D>
inline D loadLanes(const double* p) {
  D x;
  __builtin_memcpy(&x, p, sizeof(D));
  return x;
}
template <class D>
inline void storeLanes(D x, double* p) {
  __builtin_memcpy(p, &x, sizeof(D));
}
// field[0..2][o, o + W).
template <class D>
inline void loadVector(const double (&field)[3][kRowBlock], int o, D out[3]) {
  for (int j = 0; j < 3; ++j) out[j] = loadLanes<D>(field[j] + o);
}

// The addresses of the field `offset` doubles after v of the bodies ids[0, W).
template <int W>
inline void laneFields(const LaneBodies& bodies, const int32_t* ids, int offset,
                       const double* out[W]) {
  for (int l = 0; l < W; ++l) out[l] = bodies.v + long(ids[l]) * bodies.stride + offset;
}

// field[0..2][o, o + W) of a frame, rotated by q.
template <class D>
inline void rotateField(const D q[4], const double (&field)[3][kRowBlock], int o, D out[3]) {
  D v[3];
  loadVector(field, o, v);
  rotate(q, v, out);
}
// x into lanes [o, o + W) of a frame's field, and rounded into the row block's.
template <class D, int N>
inline void storeField(const D x[N], double (&field)[N][kRowBlock], float (&row)[N][kRowBlock],
                       int o) {
  for (int j = 0; j < N; ++j) {
    storeLanes(x[j], field[j] + o);
    storeFloats(x[j], row[j] + o);
  }
}

// The angles of lanes [o, o + W) advanced with the positions, and the limits' errors.
template <class D>
inline void advanceAngles(PointFrameBlock& f, PointRowBlock& r, int o, const double* const wa[],
                          const double* const wb[], double h) {
  const D far = D() + kFarOpen, one = D() + 1.0, zero = D() + 0.0, hl = D() + h;
  D w_a[3], w_b[3], dw[3];
  gather<3>(wa, w_a);
  gather<3>(wb, w_b);
  for (int j = 0; j < 3; ++j) dw[j] = w_b[j] - w_a[j];
  for (int row = 0; row < r.angle_rows; ++row) {
    D jr[3];
    for (int j = 0; j < 3; ++j) jr[j] = loadLanes<D>(f.angle_j[row][j] + o);
    const D theta = loadLanes<D>(f.angles[row] + o) + hl * dot(jr, dw);
    storeLanes(theta, f.angles[row] + o);
    const auto limited = loadLanes<D>(f.limited[row] + o) > zero;
    D lower = limited ? theta - loadLanes<D>(f.lower[row] + o) : one;
    D upper = limited ? loadLanes<D>(f.upper[row] + o) - theta : one;
    lower = far < lower ? far : lower;  // std::min(lower, far)
    upper = far < upper ? far : upper;
    storeFloats(lower, r.limit_c[row][0] + o);
    storeFloats(upper, r.limit_c[row][1] + o);
  }
}

// Lanes [o, o + W) of one block.
template <class D>
inline void refreshLanes(PointFrameBlock& f, PointRowBlock& r, int o, const LaneBodies& bodies,
                         bool advance_angles, double h) {
  constexpr int W = sizeof(D) / sizeof(double);
  const double *qa[W], *qb[W], *pa[W], *pb[W], *wa[W], *wb[W];
  laneFields<W>(bodies, f.body_a + o, kLaneDq, qa);
  laneFields<W>(bodies, f.body_b + o, kLaneDq, qb);
  laneFields<W>(bodies, f.body_a + o, kLaneDp, pa);
  laneFields<W>(bodies, f.body_b + o, kLaneDp, pb);
  laneFields<W>(bodies, f.body_a + o, 3, wa);
  laneFields<W>(bodies, f.body_b + o, 3, wb);
  if (advance_angles && r.angle_rows) advanceAngles<D>(f, r, o, wa, wb, h);
  D dqa[4], dqb[4], dpa[3], dpb[3];
  gather<4>(qa, dqa);
  gather<4>(qb, dqb);
  gather<3>(pa, dpa);
  gather<3>(pb, dpb);
  D ra[3], rb[3], c[3];
  rotateField(dqa, f.r_a0, o, ra);
  rotateField(dqb, f.r_b0, o, rb);
  for (int j = 0; j < 3; ++j)
    c[j] = ((dpb[j] - dpa[j]) + (rb[j] - ra[j])) + loadLanes<D>(f.center[j] + o);
  storeField<D, 3>(ra, f.r_a, r.r_a, o);
  storeField<D, 3>(rb, f.r_b, r.r_b, o);
  for (int j = 0; j < 3; ++j) storeFloats(c[j], r.error[j] + o);
  if (!r.axis_rows) return;
  D a1[3], b2[3], c2[3], u1[3], u2[3];
  rotateField(dqa, f.a1, o, a1);
  rotateField(dqb, f.b2, o, b2);
  rotateField(dqb, f.c2, o, c2);
  cross(b2, a1, u1);
  cross(c2, a1, u2);
  const D axis_c[2] = {dot(a1, b2), dot(a1, c2)};
  storeField<D, 3>(u1, f.u1, r.axis_u1, o);
  storeField<D, 3>(u2, f.u2, r.axis_u2, o);
  storeField<D, 2>(axis_c, f.axis_c, r.axis_error, o);
}

// Blocks [0, count), W lanes at a time up to the first padding lane's group.
template <class D>
inline void refreshBlocks(PointFrameBlock* frames, PointRowBlock* rows, int count,
                          const LaneBodies& bodies, bool advance_angles, double h) {
  constexpr int W = sizeof(D) / sizeof(double);
  for (int k = 0; k < count; ++k)
    for (int o = 0; o < kRowBlock && (rows[k].body_a[o] >= 0 || rows[k].body_b[o] >= 0); o += W)
      refreshLanes<D>(frames[k], rows[k], o, bodies, advance_angles, h);
}

}  // namespace RAGDOLL_SIM_FRAMES_ISA
}  // namespace point_frames
}  // namespace ragdoll_sim
