// Double lanes for kernels that must give the bits of the scalar Eigen code they replace:
// Double2 (an SSE2 register, the x86-64 baseline) and Double4 (an AVX register, only in a file
// compiled with -mavx2 -mno-fma), GCC vectors whose operators are the element-wise IEEE
// operations, with the gathers and scatters that move W bodies' fields in and out of them.
// As lanes.hpp: no std headers or Eigen (an AVX file includes this), and an inline namespace
// per instruction set, so that no AVX copy of an inline function replaces a baseline one.
#pragma once

#include <emmintrin.h>
#if defined(__AVX__)
#include <immintrin.h>
#endif

#if defined(__AVX2__)
#define RAGDOLL_SIM_DOUBLE_LANES_ISA double_lanes_avx2
#else
#define RAGDOLL_SIM_DOUBLE_LANES_ISA double_lanes_sse2
#endif

namespace ragdoll_sim {
namespace double_lanes {
inline namespace RAGDOLL_SIM_DOUBLE_LANES_ISA {

// Two doubles, one per body; the operators are the element-wise IEEE operations.
typedef double Double2 __attribute__((vector_size(16)));
inline double squareRoot(double x) { return __builtin_sqrt(x); }
inline Double2 squareRoot(Double2 x) { return Double2(_mm_sqrt_pd(__m128d(x))); }
#if defined(__AVX__)
typedef double Double4 __attribute__((vector_size(32)));
inline Double4 squareRoot(Double4 x) { return Double4(_mm256_sqrt_pd(__m256d(x))); }
#endif
// The widest lanes of this file's build: the *_w4.cpp kernels' (built without AVX, two lanes).
#if defined(__AVX__)
using WidestLanes = Double4;
#else
using WidestLanes = Double2;
#endif

// nearbyint in the default rounding mode (to nearest, ties to even), for |y| < 2^52: SSE2 has
// no rounding instruction, so 2^52 with y's sign is added and taken away (the sum's ulp is 1),
// and the sign goes back on a zero result, as nearbyint keeps it.
inline double roundToInteger(double y) { return __builtin_nearbyint(y); }
inline Double2 roundToInteger(Double2 y) {
  const __m128d sign = _mm_and_pd(__m128d(y), _mm_set1_pd(-0.0));
  const __m128d big = _mm_or_pd(_mm_set1_pd(4503599627370496.0), sign);
  const __m128d r = _mm_sub_pd(_mm_add_pd(__m128d(y), big), big);
  return Double2(_mm_or_pd(r, sign));
}
#if defined(__AVX__)
inline Double4 roundToInteger(Double4 y) {
  return Double4(_mm256_round_pd(__m256d(y), _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
}
#endif

// x rounded to float into p[0, W): the conversion instruction rounds to nearest, as a cast does.
inline void storeFloats(double x, float* p) { *p = float(x); }
inline void storeFloats(Double2 x, float* p) {
  _mm_storel_pi(reinterpret_cast<__m64*>(p), _mm_cvtpd_ps(__m128d(x)));
}
#if defined(__AVX__)
inline void storeFloats(Double4 x, float* p) { _mm_storeu_ps(p, _mm256_cvtpd_ps(__m256d(x))); }
#endif

// Vectors of three lanes (any D above, or double): a x b componentwise a1 b2 - a2 b1, ...;
// a . b = a0 b0 + (a1 b1 + a2 b2) (Eigen's unrolled reduction); q v (q: x, y, z, w) as Eigen's
// _transformVector: uv = q.vec x v, uv = uv + uv, then (v + q.w uv) + q.vec x uv.
template <class D>
inline void cross(const D a[3], const D b[3], D out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}
template <class D>
inline D dot(const D a[3], const D b[3]) {
  return a[0] * b[0] + (a[1] * b[1] + a[2] * b[2]);
}
// out = q v (q: x, y, z, w).
template <class D>
inline void rotate(const D q[4], const D v[3], D out[3]) {
  D uv[3], t[3];
  cross(q, v, uv);
  for (int j = 0; j < 3; ++j) uv[j] = uv[j] + uv[j];
  cross(q, uv, t);
  for (int j = 0; j < 3; ++j) out[j] = (v[j] + q[3] * uv[j]) + t[j];
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

// Whether x's sign bit is set, and |x| (std::abs's bits, a NaN's too).
inline bool signBit(double x) { return __builtin_signbit(x); }
inline double magnitude(double x) { return __builtin_fabs(x); }
template <class D>
inline auto signBit(D x) {
  using Mask = decltype(x < x);  // the integer vector of D's width
  Mask bits;
  __builtin_memcpy(&bits, &x, sizeof bits);
  return bits < Mask{};
}
template <class D>
inline D magnitude(D x) {
  return signBit(x) ? -x : x;
}

// The lanes of W bodies' arrays: out[j] = {p[0][j], ..., p[W-1][j]}, and back.
inline double lane(double x, int) { return x; }
template <class D>
inline double lane(D x, int l) {
  return x[l];
}

template <int N>
inline void gather(const double* const p[1], double out[N]) {
  for (int j = 0; j < N; ++j) out[j] = p[0][j];
}
template <int N>
inline void scatter(const double in[N], double* const p[1]) {
  for (int j = 0; j < N; ++j) p[0][j] = in[j];
}
template <int N>
inline void gather(const double* const p[2], Double2 out[N]) {
  for (int j = 0; j < N; ++j) out[j] = Double2{p[0][j], p[1][j]};
}
template <int N>
inline void scatter(const Double2 in[N], double* const p[2]) {
  for (int j = 0; j < N; ++j) {
    p[0][j] = in[j][0];
    p[1][j] = in[j][1];
  }
}
#if defined(__AVX__)
// Four rows of four doubles into four columns (and back: the transpose is its own inverse).
inline void transpose4(__m256d r0, __m256d r1, __m256d r2, __m256d r3, Double4 out[4]) {
  const __m256d t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1);
  const __m256d t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);
  out[0] = Double4(_mm256_permute2f128_pd(t0, t2, 0x20));
  out[1] = Double4(_mm256_permute2f128_pd(t1, t3, 0x20));
  out[2] = Double4(_mm256_permute2f128_pd(t0, t2, 0x31));
  out[3] = Double4(_mm256_permute2f128_pd(t1, t3, 0x31));
}
// Runs of four fields move as a 4 x 4 transpose of whole rows, the rest one double at a time.
template <int N>
inline void gather(const double* const p[4], Double4 out[N]) {
  int j = 0;
  for (; j + 4 <= N; j += 4)
    transpose4(_mm256_loadu_pd(p[0] + j), _mm256_loadu_pd(p[1] + j), _mm256_loadu_pd(p[2] + j),
               _mm256_loadu_pd(p[3] + j), out + j);
  for (; j < N; ++j) out[j] = Double4{p[0][j], p[1][j], p[2][j], p[3][j]};
}
template <int N>
inline void scatter(const Double4 in[N], double* const p[4]) {
  int j = 0;
  for (; j + 4 <= N; j += 4) {
    Double4 rows[4];
    transpose4(__m256d(in[j]), __m256d(in[j + 1]), __m256d(in[j + 2]), __m256d(in[j + 3]), rows);
    for (int l = 0; l < 4; ++l) _mm256_storeu_pd(p[l] + j, __m256d(rows[l]));
  }
  for (; j < N; ++j)
    for (int l = 0; l < 4; ++l) p[l][j] = in[j][l];
}
#endif

}  // namespace RAGDOLL_SIM_DOUBLE_LANES_ISA
}  // namespace double_lanes
}  // namespace ragdoll_sim
