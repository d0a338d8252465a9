// The rotation step of integratePositions on plain arrays, written once for a lane type D:
// double (one body), Double2 (two bodies in an SSE2 register, the x86-64 baseline) or Double4
// (four bodies in an AVX register, integrate_w4.cpp, compiled with -mavx2 -mno-fma), the lanes
// of double_lanes.hpp. Every lane does exactly the IEEE operations, in the order, of the Eigen
// expressions they replace (EIGEN_DONT_VECTORIZE: Eigen's scalar paths), so all types give the
// bits of
//   dp += h v;  L = R (I (R^T w));  dq = (dq + (0, h/2 w) dq).normalized();
//   R = (dq q).toRotationMatrix();  w = R (I^-1 (R^T L))
// and, at the step start, R = q.toRotationMatrix() and the world inverse inertia R I^-1 R^T,
// where a 3-term sum a0 + a1 + a2 is Eigen's a0 + (a1 + a2) (its unrolled reduction halves the
// range), a quaternion product sums left to right, and |c|^2 = (x^2 + y^2) + (z^2 + w^2).
// Matrices are column-major (Eigen's default), quaternions stored x, y, z, w.
// As lanes.hpp: no std headers or Eigen (the AVX file includes this), and an inline namespace
// per instruction set, so that no AVX copy of an inline function replaces a baseline one.
#pragma once

#include "double_lanes.hpp"

#if defined(__AVX2__)
#define RAGDOLL_SIM_INTEGRATE_ISA integrate_avx2
#else
#define RAGDOLL_SIM_INTEGRATE_ISA integrate_sse2
#endif

namespace ragdoll_sim {
namespace integrate_kernel {

// Where the position step finds a body's fields: each body array's base, stride and the
// fields' byte offsets, so that the kernels need no Eigen type (the AVX file cannot include it).
// Plain data outside the per-ISA namespace: both builds of the kernels take the same type.
struct BodyFields {
  char* solver;  // SolverBody array
  long solver_stride, v, w, dp, dq, world_inv_inertia;
  char* motion;  // BodyMotion array (finishPoses writes x, x_carry and q)
  long motion_stride, x, x_carry, inertia, inv_inertia, q, force, torque, gravity_scale, inv_mass,
      linear_damping, angular_damping;
  double* rotations;  // 9 per body, column-major
};

inline namespace RAGDOLL_SIM_INTEGRATE_ISA {

using double_lanes::Double2;
using double_lanes::squareRoot;
#if defined(__AVX__)
using double_lanes::Double4;
#endif
using double_lanes::gather;
using double_lanes::lane;
using double_lanes::quatProduct;
using double_lanes::rotationMatrix;
using double_lanes::roundToInteger;
using double_lanes::scatter;

// c / sqrt(z) where z > 0, c unchanged elsewhere (Eigen's normalized()).
inline void divideByRoot(double z, double c[4]) {
  if (z > 0.0) {
    const double n = squareRoot(z);
    for (int j = 0; j < 4; ++j) c[j] = c[j] / n;
  }
}
template <class D>
inline void divideByRoot(D z, D c[4]) {
  const auto positive = z > D() + 0.0;
  const D n = squareRoot(z);
  for (int j = 0; j < 4; ++j) c[j] = positive ? c[j] / n : c[j];
}

// out = M x, M column-major.
template <class D>
inline void mul(const D M[9], const D x[3], D out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = M[i] * x[0] + (M[3 + i] * x[1] + M[6 + i] * x[2]);
}

// out = M^T x.
template <class D>
inline void mulTransposed(const D M[9], const D x[3], D out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = M[3 * i] * x[0] + (M[3 * i + 1] * x[1] + M[3 * i + 2] * x[2]);
}

// x <- R (M (R^T x)).
template <class D>
inline void worldProduct(const D R[9], const D M[9], D x[3]) {
  D t[3], u[3];
  mulTransposed(R, x, t);
  mul(M, t, u);
  mul(R, u, x);
}

// The world inverse inertia R I^-1 R^T as Eigen evaluates R * I^-1 * R.transpose(): R I^-1 into
// a temporary T, then T R^T, each coefficient a row-column sum as in mul.
template <class D>
inline void worldInverseInertia(const D R[9], const D M[9], D out[9]) {
  D T[9];
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      T[3 * j + i] = R[i] * M[3 * j] + (R[3 + i] * M[3 * j + 1] + R[6 + i] * M[3 * j + 2]);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      out[3 * j + i] = T[i] * R[j] + (T[3 + i] * R[3 + j] + T[6 + i] * R[6 + j]);
}

// A body's velocity step (integrateVelocities before the clamps): gravity, force and torque,
// then damping: v = (v + h (s g + m^-1 f)) / (1 + h c), w = (w + h (I^-1 t)) / (1 + h c_w),
// where Eigen evaluates h (I^-1 t) as (h I^-1) t.
template <class D>
inline void advanceVelocity(D h, const D gravity[3], D gravity_scale, D inv_mass, const D force[3],
                            D linear_damping, D angular_damping, const D inv_inertia[9],
                            const D torque[3], D v[3], D w[3]) {
  const D one = D() + 1.0;
  D a[3], h_inv_inertia[9], h_alpha[3];
  for (int j = 0; j < 3; ++j) a[j] = gravity_scale * gravity[j] + inv_mass * force[j];
  const D linear = one + h * linear_damping;
  for (int j = 0; j < 3; ++j) v[j] = (v[j] + h * a[j]) / linear;
  for (int j = 0; j < 9; ++j) h_inv_inertia[j] = h * inv_inertia[j];
  mul(h_inv_inertia, torque, h_alpha);
  const D angular = one + h * angular_damping;
  for (int j = 0; j < 3; ++j) w[j] = (w[j] + h_alpha[j]) / angular;
}

// |x|^2 as Eigen's squaredNorm: the clamps' first test (clampNorm, fault_guard.hpp).
template <class D>
inline D squaredNorm(const D x[3]) {
  return x[0] * x[0] + (x[1] * x[1] + x[2] * x[2]);
}

// The first half of a body's position step: dp, dq and R advance, and w is replaced by the world
// angular momentum L taken with the old R (finishRotation turns it back with the new R).
// half_h: 0.5 * h, rounded as the caller's scalar product.
template <class D>
inline void advanceRotation(D h, D half_h, const D v[3], D dp[3], D w[3], D dq[4], D R[9],
                            const D inertia[9], const D q[4]) {
  for (int j = 0; j < 3; ++j) dp[j] = dp[j] + h * v[j];
  const D hw[4] = {half_h * w[0], half_h * w[1], half_h * w[2], D() + 0.0};
  worldProduct(R, inertia, w);
  D turn[4];
  quatProduct(hw, dq, turn);
  for (int j = 0; j < 4; ++j) dq[j] = dq[j] + turn[j];
  divideByRoot((dq[0] * dq[0] + dq[1] * dq[1]) + (dq[2] * dq[2] + dq[3] * dq[3]), dq);
  D c[4];
  quatProduct(dq, q, c);
  rotationMatrix(c, R);
}

// w = R (I^-1 (R^T L)) with the new R.
template <class D>
inline void finishRotation(const D R[9], const D inv_inertia[9], D w[3]) {
  worldProduct(R, inv_inertia, w);
}

inline double* solverField(const BodyFields& f, int body, long offset) {
  return (double*)(f.solver + body * f.solver_stride + offset);
}
inline double* motionField(const BodyFields& f, int body, long offset) {
  return (double*)(f.motion + body * f.motion_stride + offset);
}

// The position step (advanceRotation, then finishRotation) of bodies[0..count), W = sizeof(D) / 8
// at a time; count a multiple of W. The W bodies' chains run side by side in the lanes, so one
// loop does both halves (the scalar code splits them to let the core overlap bodies).
template <class D>
inline void stepPositions(const BodyFields& f, const int* bodies, int count, double h,
                             double half_h) {
  constexpr int W = sizeof(D) / sizeof(double);
  const D hl = D() + h, half_hl = D() + half_h;
  for (int k = 0; k < count; k += W) {
    const double *v[W], *inertia[W], *inv_inertia[W], *q[W];
    double *dp[W], *w[W], *dq[W], *R[W];
    for (int l = 0; l < W; ++l) {
      const int b = bodies[k + l];
      v[l] = solverField(f, b, f.v);
      dp[l] = solverField(f, b, f.dp);
      w[l] = solverField(f, b, f.w);
      dq[l] = solverField(f, b, f.dq);
      R[l] = f.rotations + 9 * b;
      inertia[l] = motionField(f, b, f.inertia);
      inv_inertia[l] = motionField(f, b, f.inv_inertia);
      q[l] = motionField(f, b, f.q);
    }
    D vl[3], dpl[3], wl[3], dql[4], Rl[9], inertial[9], ql[4];
    gather<3>(v, vl);
    gather<3>(dp, dpl);
    gather<3>(w, wl);
    gather<4>(dq, dql);
    gather<9>(R, Rl);
    gather<9>(inertia, inertial);
    gather<4>(q, ql);
    advanceRotation(hl, half_hl, vl, dpl, wl, dql, Rl, inertial, ql);
    D inv_inertial[9];
    gather<9>(inv_inertia, inv_inertial);
    finishRotation(Rl, inv_inertial, wl);
    scatter<3>(dpl, dp);
    scatter<3>(wl, w);
    scatter<4>(dql, dq);
    scatter<9>(Rl, R);
  }
}

// The step-start rotation R = q.toRotationMatrix() and world inverse inertia of bodies[0..count),
// W at a time as stepPositions (prepareSolverBodies).
template <class D>
inline void prepareRotations(const BodyFields& f, const int* bodies, int count) {
  constexpr int W = sizeof(D) / sizeof(double);
  for (int k = 0; k < count; k += W) {
    const double *q[W], *inv_inertia[W];
    double *R[W], *world[W];
    for (int l = 0; l < W; ++l) {
      const int b = bodies[k + l];
      q[l] = motionField(f, b, f.q);
      inv_inertia[l] = motionField(f, b, f.inv_inertia);
      R[l] = f.rotations + 9 * b;
      world[l] = solverField(f, b, f.world_inv_inertia);
    }
    D ql[4], Rl[9], Ml[9], out[9];
    gather<4>(q, ql);
    gather<9>(inv_inertia, Ml);
    rotationMatrix(ql, Rl);
    worldInverseInertia(Rl, Ml, out);
    scatter<9>(Rl, R);
    scatter<9>(out, world);
  }
}

// x on the position grid (body.hpp's snapPosition): nearbyint(x 2^32) / 2^32 within the world
// range, x beyond it.
template <class D>
inline D snapToGrid(D x, D grid, D range) {
  const auto within = (x < D() + 0.0 ? -x : x) < range;
  return within ? roundToInteger(x * grid) / grid : x;
}

// The pose part of finishBody on bodies[0..count), W at a time as stepPositions: the step's
// displacement goes onto the grid with the carry, q = (dq q).normalized().
// grid, range: body.hpp's 2^32 steps per metre and kWorldRange.
template <class D>
inline void finishPoses(const BodyFields& f, const int* bodies, int count, double grid,
                        double range) {
  constexpr int W = sizeof(D) / sizeof(double);
  const D gridl = D() + grid, rangel = D() + range;
  for (int k = 0; k < count; k += W) {
    const double *dp[W], *dq[W];
    double *x[W], *carry[W], *q[W];
    for (int l = 0; l < W; ++l) {
      const int b = bodies[k + l];
      dp[l] = solverField(f, b, f.dp);
      dq[l] = solverField(f, b, f.dq);
      x[l] = motionField(f, b, f.x);
      carry[l] = motionField(f, b, f.x_carry);
      q[l] = motionField(f, b, f.q);
    }
    D dpl[3], xl[3], carryl[3], dql[4], ql[4], out[4];
    gather<3>(dp, dpl);
    gather<3>(x, xl);
    gather<3>(carry, carryl);
    gather<4>(dq, dql);
    gather<4>(q, ql);
    for (int j = 0; j < 3; ++j) {
      const D d = dpl[j] + carryl[j];
      const D on_grid = snapToGrid(d, gridl, rangel);
      carryl[j] = d - on_grid;
      xl[j] = xl[j] + on_grid;
    }
    quatProduct(dql, ql, out);
    divideByRoot((out[0] * out[0] + out[1] * out[1]) + (out[2] * out[2] + out[3] * out[3]), out);
    scatter<3>(xl, x);
    scatter<3>(carryl, carry);
    scatter<4>(out, q);
  }
}

// advanceVelocity on bodies[0..count), W at a time as stepPositions; gravity: 3 doubles. The
// indices k of the bodies whose v or w fails clampNorm's first test (|v|^2 <= max_v^2, the same
// for w, NaN fails) go to clamp[], their number is returned: only those need clampNorm.
template <class D>
inline int advanceVelocities(const BodyFields& f, const int* bodies, int count, double h,
                             const double* gravity, double max_v2, double max_w2, int* clamp) {
  constexpr int W = sizeof(D) / sizeof(double);
  const D hl = D() + h;
  const D g[3] = {D() + gravity[0], D() + gravity[1], D() + gravity[2]};
  int clamped = 0;
  for (int k = 0; k < count; k += W) {
    const double *force[W], *torque[W], *inv_inertia[W], *scalars[4][W];
    double *v[W], *w[W];
    for (int l = 0; l < W; ++l) {
      const int b = bodies[k + l];
      v[l] = solverField(f, b, f.v);
      w[l] = solverField(f, b, f.w);
      inv_inertia[l] = solverField(f, b, f.world_inv_inertia);
      force[l] = motionField(f, b, f.force);
      torque[l] = motionField(f, b, f.torque);
      scalars[0][l] = motionField(f, b, f.gravity_scale);
      scalars[1][l] = motionField(f, b, f.inv_mass);
      scalars[2][l] = motionField(f, b, f.linear_damping);
      scalars[3][l] = motionField(f, b, f.angular_damping);
    }
    D vl[3], wl[3], forcel[3], torquel[3], inv_inertial[9], sl[4][1];
    gather<3>(v, vl);
    gather<3>(w, wl);
    gather<3>(force, forcel);
    gather<3>(torque, torquel);
    gather<9>(inv_inertia, inv_inertial);
    for (int j = 0; j < 4; ++j) gather<1>(scalars[j], sl[j]);
    advanceVelocity(hl, g, sl[0][0], sl[1][0], forcel, sl[2][0], sl[3][0], inv_inertial, torquel,
                    vl, wl);
    scatter<3>(vl, v);
    scatter<3>(wl, w);
    const D sv = squaredNorm(vl), sw = squaredNorm(wl);
    for (int l = 0; l < W; ++l)
      if (!(lane(sv, l) <= max_v2 && lane(sw, l) <= max_w2)) clamp[clamped++] = k + l;
  }
  return clamped;
}

}  // namespace RAGDOLL_SIM_INTEGRATE_ISA
}  // namespace integrate_kernel

// The four-body kernels (integrate_w4.cpp), for a CPU with AVX2 (cpuHasAvx2); count a multiple
// of 4. Built for the baseline (no AVX2 compiler), they run the two-body kernels instead.
namespace integrate_w4 {
void stepPositions(const integrate_kernel::BodyFields& f, const int* bodies, int count, double h,
                   double half_h);
int advanceVelocities(const integrate_kernel::BodyFields& f, const int* bodies, int count, double h,
                      const double* gravity, double max_v2, double max_w2, int* clamp);
void prepareRotations(const integrate_kernel::BodyFields& f, const int* bodies, int count);
void finishPoses(const integrate_kernel::BodyFields& f, const int* bodies, int count, double grid,
                 double range);
}  // namespace integrate_w4
}  // namespace ragdoll_sim
