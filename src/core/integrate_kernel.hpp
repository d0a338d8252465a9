// The rotation step of integratePositions on plain arrays, written once for a lane type D:
// double (one body) or Double2 (two bodies in the two halves of an SSE2 register, the x86-64
// baseline). Every lane does exactly the IEEE operations, in the order, of the Eigen expressions
// they replace (EIGEN_DONT_VECTORIZE: Eigen's scalar paths), so both types give the bits of
//   dp += h v;  L = R (I (R^T w));  dq = (dq + (0, h/2 w) dq).normalized();
//   R = (dq q).toRotationMatrix();  w = R (I^-1 (R^T L))
// where a 3-term sum a0 + a1 + a2 is Eigen's a0 + (a1 + a2) (its unrolled reduction halves the
// range), a quaternion product sums left to right, and |c|^2 = (x^2 + y^2) + (z^2 + w^2).
// Matrices are column-major (Eigen's default), quaternions stored x, y, z, w.
#pragma once

#include <emmintrin.h>

#include <cmath>

namespace ragdoll_sim {
namespace integrate_kernel {

// Two doubles, one per body; the operators are the element-wise IEEE operations.
typedef double Double2 __attribute__((vector_size(16)));

inline double squareRoot(double x) { return std::sqrt(x); }
inline Double2 squareRoot(Double2 x) { return Double2(_mm_sqrt_pd(__m128d(x))); }

// c / sqrt(z) where z > 0, c unchanged elsewhere (Eigen's normalized()).
inline void divideByRoot(double z, double c[4]) {
  if (z > 0.0) {
    const double n = squareRoot(z);
    for (int j = 0; j < 4; ++j) c[j] = c[j] / n;
  }
}
inline void divideByRoot(Double2 z, Double2 c[4]) {
  const Double2 zero = {0.0, 0.0};
  const auto positive = z > zero;
  const Double2 n = squareRoot(z);
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

// out = a b (Eigen's quat_product), quaternions x, y, z, w.
template <class D>
inline void quatProduct(const D a[4], const D b[4], D out[4]) {
  out[3] = a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2];
  out[0] = a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1];
  out[1] = a[3] * b[1] + a[1] * b[3] + a[2] * b[0] - a[0] * b[2];
  out[2] = a[3] * b[2] + a[2] * b[3] + a[0] * b[1] - a[1] * b[0];
}

// R of the unit quaternion c (Eigen's toRotationMatrix), column-major.
template <class D>
inline void rotationMatrix(const D c[4], D R[9]) {
  const D two = D() + 2.0, one = D() + 1.0;
  const D tx = two * c[0], ty = two * c[1], tz = two * c[2];
  const D twx = tx * c[3], twy = ty * c[3], twz = tz * c[3];
  const D txx = tx * c[0], txy = ty * c[0], txz = tz * c[0];
  const D tyy = ty * c[1], tyz = tz * c[1], tzz = tz * c[2];
  R[0] = one - (tyy + tzz);
  R[3] = txy - twz;
  R[6] = txz + twy;
  R[1] = txy + twz;
  R[4] = one - (txx + tzz);
  R[7] = tyz - twx;
  R[2] = txz - twy;
  R[5] = tyz + twx;
  R[8] = one - (txx + tyy);
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

// Lanes of two bodies' arrays: out[j] = {a[j], b[j]}, and back.
template <int N>
inline void gather(const double* a, const double* b, Double2 out[N]) {
  for (int j = 0; j < N; ++j) out[j] = Double2{a[j], b[j]};
}
template <int N>
inline void scatter(const Double2 in[N], double* a, double* b) {
  for (int j = 0; j < N; ++j) {
    a[j] = in[j][0];
    b[j] = in[j][1];
  }
}

}  // namespace integrate_kernel
}  // namespace ragdoll_sim
