// Float lanes for the wide solver: FloatW<W> holds W floats and MaskW<W> W lane masks, with the
// operations the wide rows need. W = 4 is SSE2 (the x86-64 baseline), W = 8 is AVX (built only
// in a kernel file compiled with -mavx2), any other W or a target without them is a plain array.
// FloatPair16<S> (AVX-512F, built only in a file compiled with -mavx512f) holds the lanes of two
// 8-lane records S floats apart, so that an 8-lane kernel solves two records at once.
//
// Every operation (sqrt included) is one correctly rounded IEEE float operation per lane (no reciprocal or
// square-root estimates, no fused multiply-add), so a formula gives the same bits in each lane
// whatever W and whatever the instruction set; kernel files are compiled with -ffp-contract=off
// so that the compiler does not fuse a product and a sum on its own either.
// min and max follow the SSE rule, min(a, b) = a < b ? a : b and max(a, b) = a > b ? a : b
// (the second operand for NaN or equal zeros), in every implementation.
//
// Everything here lives in an inline namespace named after the instruction set the including
// file is compiled for: a file built with -mavx2 and one built for the baseline both include
// this header, and with one name their copies of the same inline function would be merged at
// link time, so the baseline code could end up calling an AVX copy on a CPU without AVX.
// For the same reason a file compiled with -mavx2 includes nothing but this header and plain
// declarations (no std templates, no Eigen).
#pragma once

#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__AVX__)
#include <immintrin.h>
#endif

#if defined(__AVX512F__)
#define RAGDOLL_SIM_LANES_ISA lanes_avx512
#elif defined(__AVX2__)
#define RAGDOLL_SIM_LANES_ISA lanes_avx2
#elif defined(__SSE2__)
#define RAGDOLL_SIM_LANES_ISA lanes_sse2
#else
#define RAGDOLL_SIM_LANES_ISA lanes_generic
#endif

namespace ragdoll_sim {
inline namespace RAGDOLL_SIM_LANES_ISA {

// The portable lanes: a plain array, one scalar operation per lane.
template <int W>
struct MaskArrayW {
  uint32_t m[W];  // all ones or zero
  friend MaskArrayW operator&(MaskArrayW a, MaskArrayW b) {
    for (int i = 0; i < W; ++i) a.m[i] &= b.m[i];
    return a;
  }
  friend MaskArrayW operator|(MaskArrayW a, MaskArrayW b) {
    for (int i = 0; i < W; ++i) a.m[i] |= b.m[i];
    return a;
  }
  // a and not b
  friend MaskArrayW andNot(MaskArrayW a, MaskArrayW b) {
    for (int i = 0; i < W; ++i) a.m[i] &= ~b.m[i];
    return a;
  }
  // Bit i set when lane i is true.
  int bits() const {
    int r = 0;
    for (int i = 0; i < W; ++i) r |= int(m[i] & 1u) << i;
    return r;
  }
  bool any() const { return bits() != 0; }
  bool all() const { return bits() == (1 << W) - 1; }
};

template <int W>
struct FloatArrayW {
  static constexpr int kWidth = W;
  using Mask = MaskArrayW<W>;
  float v[W];

  static FloatArrayW zero() { return splat(0.0f); }
  static FloatArrayW splat(float x) {
    FloatArrayW r;
    for (int i = 0; i < W; ++i) r.v[i] = x;
    return r;
  }
  // p aligned to 4 W bytes (load/store) or not (loadu/storeu): the same for the array.
  static FloatArrayW load(const float* p) { return loadu(p); }
  static FloatArrayW loadu(const float* p) {
    FloatArrayW r;
    for (int i = 0; i < W; ++i) r.v[i] = p[i];
    return r;
  }
  void store(float* p) const { storeu(p); }
  void storeu(float* p) const {
    for (int i = 0; i < W; ++i) p[i] = v[i];
  }
  float lane(int i) const { return v[i]; }
  // field[index[i]] in lane i, 0 where index[i] < 0.
  static FloatArrayW gather(const float* field, const int32_t* index) {
    FloatArrayW r;
    for (int i = 0; i < W; ++i) r.v[i] = index[i] >= 0 ? field[index[i]] : 0.0f;
    return r;
  }

#define RAGDOLL_SIM_ARRAY_OP(NAME, EXPR)                       \
  friend FloatArrayW NAME(FloatArrayW a, FloatArrayW b) {      \
    FloatArrayW r;                                             \
    for (int i = 0; i < W; ++i) r.v[i] = EXPR;                 \
    return r;                                                  \
  }
  RAGDOLL_SIM_ARRAY_OP(operator+, a.v[i] + b.v[i])
  RAGDOLL_SIM_ARRAY_OP(operator-, a.v[i] - b.v[i])
  RAGDOLL_SIM_ARRAY_OP(operator*, a.v[i] * b.v[i])
  RAGDOLL_SIM_ARRAY_OP(operator/, a.v[i] / b.v[i])
  RAGDOLL_SIM_ARRAY_OP(min, a.v[i] < b.v[i] ? a.v[i] : b.v[i])
  RAGDOLL_SIM_ARRAY_OP(max, a.v[i] > b.v[i] ? a.v[i] : b.v[i])
#undef RAGDOLL_SIM_ARRAY_OP
  friend FloatArrayW sqrt(FloatArrayW a) {
    for (int i = 0; i < W; ++i) a.v[i] = __builtin_sqrtf(a.v[i]);
    return a;
  }

#define RAGDOLL_SIM_ARRAY_CMP(NAME, OP)                        \
  friend Mask NAME(FloatArrayW a, FloatArrayW b) {             \
    Mask r;                                                    \
    for (int i = 0; i < W; ++i) r.m[i] = a.v[i] OP b.v[i] ? ~0u : 0u; \
    return r;                                                  \
  }
  RAGDOLL_SIM_ARRAY_CMP(operator<, <)
  RAGDOLL_SIM_ARRAY_CMP(operator<=, <=)
  RAGDOLL_SIM_ARRAY_CMP(operator>, >)
  RAGDOLL_SIM_ARRAY_CMP(operator>=, >=)
  RAGDOLL_SIM_ARRAY_CMP(operator==, ==)
#undef RAGDOLL_SIM_ARRAY_CMP

  // mask ? a : b, lane by lane.
  friend FloatArrayW select(Mask mask, FloatArrayW a, FloatArrayW b) {
    FloatArrayW r;
    for (int i = 0; i < W; ++i) r.v[i] = mask.m[i] ? a.v[i] : b.v[i];
    return r;
  }
};

#if defined(__SSE2__)
struct Mask4 {
  __m128 m;
  friend Mask4 operator&(Mask4 a, Mask4 b) { return {_mm_and_ps(a.m, b.m)}; }
  friend Mask4 operator|(Mask4 a, Mask4 b) { return {_mm_or_ps(a.m, b.m)}; }
  friend Mask4 andNot(Mask4 a, Mask4 b) { return {_mm_andnot_ps(b.m, a.m)}; }
  int bits() const { return _mm_movemask_ps(m); }
  bool any() const { return bits() != 0; }
  bool all() const { return bits() == 0xF; }
};

struct Float4 {
  static constexpr int kWidth = 4;
  using Mask = Mask4;
  __m128 v;

  static Float4 zero() { return {_mm_setzero_ps()}; }
  static Float4 splat(float x) { return {_mm_set1_ps(x)}; }
  static Float4 load(const float* p) { return {_mm_load_ps(p)}; }  // 16-byte aligned
  static Float4 loadu(const float* p) { return {_mm_loadu_ps(p)}; }
  void store(float* p) const { _mm_store_ps(p, v); }
  void storeu(float* p) const { _mm_storeu_ps(p, v); }
  float lane(int i) const {
    alignas(16) float t[4];
    store(t);
    return t[i];
  }
  // Lanes built from scalar loads in registers (a buffer written lane by lane and read back
  // whole stalls store forwarding); a static lane reads field[0] and is masked to 0.
  static Float4 gather(const float* field, const int32_t* index) {
    const __m128i idx = _mm_loadu_si128(reinterpret_cast<const __m128i*>(index));
    const __m128 live = _mm_castsi128_ps(_mm_cmpgt_epi32(idx, _mm_set1_epi32(-1)));
    auto at = [&](int i) { return field[index[i] < 0 ? 0 : index[i]]; };
    return {_mm_and_ps(_mm_setr_ps(at(0), at(1), at(2), at(3)), live)};
  }

  friend Float4 operator+(Float4 a, Float4 b) { return {_mm_add_ps(a.v, b.v)}; }
  friend Float4 operator-(Float4 a, Float4 b) { return {_mm_sub_ps(a.v, b.v)}; }
  friend Float4 operator*(Float4 a, Float4 b) { return {_mm_mul_ps(a.v, b.v)}; }
  friend Float4 operator/(Float4 a, Float4 b) { return {_mm_div_ps(a.v, b.v)}; }
  friend Float4 min(Float4 a, Float4 b) { return {_mm_min_ps(a.v, b.v)}; }
  friend Float4 max(Float4 a, Float4 b) { return {_mm_max_ps(a.v, b.v)}; }
  friend Float4 sqrt(Float4 a) { return {_mm_sqrt_ps(a.v)}; }
  friend Mask4 operator<(Float4 a, Float4 b) { return {_mm_cmplt_ps(a.v, b.v)}; }
  friend Mask4 operator<=(Float4 a, Float4 b) { return {_mm_cmple_ps(a.v, b.v)}; }
  friend Mask4 operator>(Float4 a, Float4 b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
  friend Mask4 operator>=(Float4 a, Float4 b) { return {_mm_cmpge_ps(a.v, b.v)}; }
  friend Mask4 operator==(Float4 a, Float4 b) { return {_mm_cmpeq_ps(a.v, b.v)}; }
  // SSE2 has no blend: (mask & a) | (~mask & b).
  friend Float4 select(Mask4 mask, Float4 a, Float4 b) {
    return {_mm_or_ps(_mm_and_ps(mask.m, a.v), _mm_andnot_ps(mask.m, b.v))};
  }
};
#endif

#if defined(__AVX__)
struct Mask8 {
  __m256 m;
  friend Mask8 operator&(Mask8 a, Mask8 b) { return {_mm256_and_ps(a.m, b.m)}; }
  friend Mask8 operator|(Mask8 a, Mask8 b) { return {_mm256_or_ps(a.m, b.m)}; }
  friend Mask8 andNot(Mask8 a, Mask8 b) { return {_mm256_andnot_ps(b.m, a.m)}; }
  int bits() const { return _mm256_movemask_ps(m); }
  bool any() const { return bits() != 0; }
  bool all() const { return bits() == 0xFF; }
};

struct Float8 {
  static constexpr int kWidth = 8;
  using Mask = Mask8;
  __m256 v;

  static Float8 zero() { return {_mm256_setzero_ps()}; }
  static Float8 splat(float x) { return {_mm256_set1_ps(x)}; }
  static Float8 load(const float* p) { return {_mm256_load_ps(p)}; }  // 32-byte aligned
  static Float8 loadu(const float* p) { return {_mm256_loadu_ps(p)}; }
  void store(float* p) const { _mm256_store_ps(p, v); }
  void storeu(float* p) const { _mm256_storeu_ps(p, v); }
  float lane(int i) const {
    alignas(32) float t[8];
    store(t);
    return t[i];
  }
  // As Float4::gather (no gather instruction: it is no faster here and AVX lacks it).
  static Float8 gather(const float* field, const int32_t* index) {
    const __m256i idx = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(index));
    const __m256 live = _mm256_castsi256_ps(_mm256_cmpgt_epi32(idx, _mm256_set1_epi32(-1)));
    auto at = [&](int i) { return field[index[i] < 0 ? 0 : index[i]]; };
    return {_mm256_and_ps(
        _mm256_setr_ps(at(0), at(1), at(2), at(3), at(4), at(5), at(6), at(7)), live)};
  }

  friend Float8 operator+(Float8 a, Float8 b) { return {_mm256_add_ps(a.v, b.v)}; }
  friend Float8 operator-(Float8 a, Float8 b) { return {_mm256_sub_ps(a.v, b.v)}; }
  friend Float8 operator*(Float8 a, Float8 b) { return {_mm256_mul_ps(a.v, b.v)}; }
  friend Float8 operator/(Float8 a, Float8 b) { return {_mm256_div_ps(a.v, b.v)}; }
  friend Float8 min(Float8 a, Float8 b) { return {_mm256_min_ps(a.v, b.v)}; }
  friend Float8 max(Float8 a, Float8 b) { return {_mm256_max_ps(a.v, b.v)}; }
  friend Float8 sqrt(Float8 a) { return {_mm256_sqrt_ps(a.v)}; }
  // Ordered, non-signalling predicates: the same truth table as the SSE2 compares.
  friend Mask8 operator<(Float8 a, Float8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)}; }
  friend Mask8 operator<=(Float8 a, Float8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ)}; }
  friend Mask8 operator>(Float8 a, Float8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)}; }
  friend Mask8 operator>=(Float8 a, Float8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GE_OQ)}; }
  friend Mask8 operator==(Float8 a, Float8 b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_EQ_OQ)}; }
  friend Float8 select(Mask8 mask, Float8 a, Float8 b) {
    return {_mm256_blendv_ps(b.v, a.v, mask.m)};
  }
};
#endif

#if defined(__AVX512F__)
struct Mask16 {
  __mmask16 m;
  friend Mask16 operator&(Mask16 a, Mask16 b) { return {__mmask16(a.m & b.m)}; }
  friend Mask16 operator|(Mask16 a, Mask16 b) { return {__mmask16(a.m | b.m)}; }
  friend Mask16 andNot(Mask16 a, Mask16 b) { return {__mmask16(a.m & ~b.m)}; }
  int bits() const { return m; }
  bool any() const { return m != 0; }
  bool all() const { return m == 0xFFFF; }
};

// Lanes 0-7 at p, lanes 8-15 at p + S (the same field of the next record).
template <int S>
struct FloatPair16 {
  static constexpr int kWidth = 16;
  using Mask = Mask16;
  __m512 v;

  static FloatPair16 zero() { return {_mm512_setzero_ps()}; }
  static FloatPair16 splat(float x) { return {_mm512_set1_ps(x)}; }
  static FloatPair16 join(__m256 lo, __m256 hi) {
    return {_mm512_castpd_ps(_mm512_insertf64x4(_mm512_castps_pd(_mm512_castps256_ps512(lo)),
                                                _mm256_castps_pd(hi), 1))};
  }
  static FloatPair16 load(const float* p) {  // both runs 32-byte aligned
    return join(_mm256_load_ps(p), _mm256_load_ps(p + S));
  }
  __m256 low() const { return _mm512_castps512_ps256(v); }
  __m256 high() const { return _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(v), 1)); }
  void store(float* p) const {
    _mm256_store_ps(p, low());
    _mm256_store_ps(p + S, high());
  }

  friend FloatPair16 operator+(FloatPair16 a, FloatPair16 b) { return {_mm512_add_ps(a.v, b.v)}; }
  friend FloatPair16 operator-(FloatPair16 a, FloatPair16 b) { return {_mm512_sub_ps(a.v, b.v)}; }
  friend FloatPair16 operator*(FloatPair16 a, FloatPair16 b) { return {_mm512_mul_ps(a.v, b.v)}; }
  friend FloatPair16 operator/(FloatPair16 a, FloatPair16 b) { return {_mm512_div_ps(a.v, b.v)}; }
  friend FloatPair16 min(FloatPair16 a, FloatPair16 b) { return {_mm512_min_ps(a.v, b.v)}; }
  friend FloatPair16 max(FloatPair16 a, FloatPair16 b) { return {_mm512_max_ps(a.v, b.v)}; }
  friend FloatPair16 sqrt(FloatPair16 a) { return {_mm512_sqrt_ps(a.v)}; }
  friend Mask16 operator<(FloatPair16 a, FloatPair16 b) {
    return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LT_OQ)};
  }
  friend Mask16 operator<=(FloatPair16 a, FloatPair16 b) {
    return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LE_OQ)};
  }
  friend Mask16 operator>(FloatPair16 a, FloatPair16 b) {
    return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_GT_OQ)};
  }
  friend Mask16 operator>=(FloatPair16 a, FloatPair16 b) {
    return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_GE_OQ)};
  }
  friend Mask16 operator==(FloatPair16 a, FloatPair16 b) {
    return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_EQ_OQ)};
  }
  friend FloatPair16 select(Mask16 mask, FloatPair16 a, FloatPair16 b) {
    return {_mm512_mask_blend_ps(mask.m, b.v, a.v)};
  }
};
#endif

template <int W>
struct FloatWSelect {
  using type = FloatArrayW<W>;
};
#if defined(__SSE2__)
template <>
struct FloatWSelect<4> {
  using type = Float4;
};
#endif
#if defined(__AVX__)
template <>
struct FloatWSelect<8> {
  using type = Float8;
};
#endif

// The fastest lanes of width W this file is compiled for.
template <int W>
using FloatW = typename FloatWSelect<W>::type;

// Lane i of a structure-of-arrays field: W consecutive floats starting at p (gather-free access:
// a record stores each field as a run of lanes).
template <class F>
F loadLanes(const float* p) {
  return F::load(p);
}

// Per-lane body fields read through an index (a body shared by several records): lane i takes
// field[index[i]], or 0 where index[i] < 0 (a static body; field holds at least one element).
// Scalar loads, no gather instruction, which SSE2 lacks.
template <class F>
F gatherLanes(const float* field, const int32_t* index) {
  return F::gather(field, index);
}
// The inverse: lanes with index >= 0 are written back (the rows of one block share no body).
template <class F>
void scatterLanes(float* field, const int32_t* index, F x) {
  alignas(32) float t[F::kWidth];
  x.store(t);
  for (int i = 0; i < F::kWidth; ++i)
    if (index[i] >= 0) field[index[i]] = t[i];
}

}  // namespace RAGDOLL_SIM_LANES_ISA
}  // namespace ragdoll_sim
