#pragma once
// Four floats in one register: SSE on x86-64 (part of the base instruction set, so one binary
// runs on any x86-64 without run-time dispatch), a plain array elsewhere. Only what the BVH's
// culling tests need (metric/triangle_bvh.cpp); IEEE single precision, no fast-math.
#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace meshdev::simd {

#if defined(__SSE2__)

struct F4 {
  __m128 v;
  static F4 load(const float* p) { return {_mm_load_ps(p)}; }  // p 16-byte aligned
  static F4 splat(float x) { return {_mm_set1_ps(x)}; }
};
inline F4 operator+(F4 a, F4 b) { return {_mm_add_ps(a.v, b.v)}; }
inline F4 operator-(F4 a, F4 b) { return {_mm_sub_ps(a.v, b.v)}; }
inline F4 operator*(F4 a, F4 b) { return {_mm_mul_ps(a.v, b.v)}; }
inline F4 operator/(F4 a, F4 b) { return {_mm_div_ps(a.v, b.v)}; }
// max/min: the second operand is returned when either is NaN (SSE semantics), so callers put the
// value that must survive a NaN second.
inline F4 max(F4 a, F4 b) { return {_mm_max_ps(a.v, b.v)}; }
inline F4 min(F4 a, F4 b) { return {_mm_min_ps(a.v, b.v)}; }
inline F4 abs(F4 a) { return {_mm_andnot_ps(_mm_set1_ps(-0.0f), a.v)}; }
inline F4 sqrt(F4 a) { return {_mm_sqrt_ps(a.v)}; }  // correctly rounded
// Bit k set when lane k satisfies a > b (false for NaN lanes).
inline int greater_mask(F4 a, F4 b) { return _mm_movemask_ps(_mm_cmpgt_ps(a.v, b.v)); }
// Bit k set when lane k of a equals lane k of b.
inline int equal_mask(F4 a, F4 b) { return _mm_movemask_ps(_mm_cmpeq_ps(a.v, b.v)); }
inline void store(float* p, F4 a) { _mm_storeu_ps(p, a.v); }

#else

struct F4 {
  float v[4];
  static F4 load(const float* p) { return {{p[0], p[1], p[2], p[3]}}; }
  static F4 splat(float x) { return {{x, x, x, x}}; }
};
#define MESHDEV_F4_BINARY(op)                                            \
  inline F4 operator op(F4 a, F4 b) {                                    \
    return {{a.v[0] op b.v[0], a.v[1] op b.v[1], a.v[2] op b.v[2], a.v[3] op b.v[3]}}; \
  }
MESHDEV_F4_BINARY(+)
MESHDEV_F4_BINARY(-)
MESHDEV_F4_BINARY(*)
MESHDEV_F4_BINARY(/)
#undef MESHDEV_F4_BINARY
inline F4 max(F4 a, F4 b) {
  F4 r;
  for (int k = 0; k < 4; ++k) r.v[k] = a.v[k] > b.v[k] ? a.v[k] : b.v[k];
  return r;
}
inline F4 min(F4 a, F4 b) {
  F4 r;
  for (int k = 0; k < 4; ++k) r.v[k] = a.v[k] < b.v[k] ? a.v[k] : b.v[k];
  return r;
}
inline F4 abs(F4 a) {
  F4 r;
  for (int k = 0; k < 4; ++k) r.v[k] = std::fabs(a.v[k]);
  return r;
}
inline F4 sqrt(F4 a) {
  F4 r;
  for (int k = 0; k < 4; ++k) r.v[k] = std::sqrt(a.v[k]);
  return r;
}
inline int greater_mask(F4 a, F4 b) {
  int m = 0;
  for (int k = 0; k < 4; ++k) m |= (a.v[k] > b.v[k]) << k;
  return m;
}
inline int equal_mask(F4 a, F4 b) {
  int m = 0;
  for (int k = 0; k < 4; ++k) m |= (a.v[k] == b.v[k]) << k;
  return m;
}
inline void store(float* p, F4 a) {
  for (int k = 0; k < 4; ++k) p[k] = a.v[k];
}

#endif

// Squared distances from the box [qlo, qhi] to four boxes [blo, bhi] (float frame): per axis the
// gap max(max(blo - qhi, qlo - bhi), 0), squared and summed in axis order. Float rounding is
// relative (far below 1e-5), and never makes a gap larger than a point's in the box.
// (metric/leaf_gather_avx2.cpp performs the same operations in its own code.)
inline F4 box_gap2(const F4 blo[3], const F4 bhi[3], const F4 qlo[3], const F4 qhi[3]) {
  const F4 zero = F4::splat(0.0f);
  F4 d2 = zero;
  for (int k = 0; k < 3; ++k) {
    const F4 d = max(max(blo[k] - qhi[k], qlo[k] - bhi[k]), zero);
    d2 = d2 + d * d;
  }
  return d2;
}

}  // namespace meshdev::simd
