#pragma once
// Two doubles in one register: SSE2 on x86-64 (part of the base instruction set, so one binary
// runs on any x86-64 without run-time dispatch), a plain array elsewhere. Only what the deviation
// loop needs to compute two samples' deviations at once (metric/attribute_deviation.cpp). Each
// lane gets exactly the IEEE double operation its scalar twin would: add, subtract, multiply,
// divide and square root are correctly rounded either way, so a lane's result is bit for bit
// the scalar one when the operations come in the same order. No fast-math, no fused
// multiply-add.
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace meshdev::simd {

#if defined(__SSE2__)

struct D2 {
  __m128d v;
  static D2 pair(double lane0, double lane1) { return {_mm_set_pd(lane1, lane0)}; }
  static D2 splat(double x) { return {_mm_set1_pd(x)}; }
};
// A lane mask (all ones or all zeros per lane).
struct M2 {
  __m128d v;
};
inline D2 operator+(D2 a, D2 b) {
  return {_mm_add_pd(a.v, b.v)};
}
inline D2 operator-(D2 a, D2 b) {
  return {_mm_sub_pd(a.v, b.v)};
}
inline D2 operator*(D2 a, D2 b) {
  return {_mm_mul_pd(a.v, b.v)};
}
inline D2 operator/(D2 a, D2 b) {
  return {_mm_div_pd(a.v, b.v)};
}
// Correctly rounded, as std::sqrt.
inline D2 sqrt(D2 a) {
  return {_mm_sqrt_pd(a.v)};
}
// Lanes where a > 0 (false for NaN), where a == 0 (true for -0).
inline M2 positive(D2 a) {
  return {_mm_cmpgt_pd(a.v, _mm_setzero_pd())};
}
inline M2 zero(D2 a) {
  return {_mm_cmpeq_pd(a.v, _mm_setzero_pd())};
}
inline M2 operator&(M2 a, M2 b) {
  return {_mm_and_pd(a.v, b.v)};
}
inline M2 operator|(M2 a, M2 b) {
  return {_mm_or_pd(a.v, b.v)};
}
// a where the mask is set, +0 elsewhere.
inline D2 keep(M2 m, D2 a) {
  return {_mm_and_pd(m.v, a.v)};
}
// Bit k set when lane k of the mask is.
inline int bits(M2 m) {
  return _mm_movemask_pd(m.v);
}
inline void store(double out[2], D2 a) {
  _mm_storeu_pd(out, a.v);
}

#else

struct D2 {
  double v[2];
  static D2 pair(double lane0, double lane1) { return {{lane0, lane1}}; }
  static D2 splat(double x) { return {{x, x}}; }
};
struct M2 {
  bool v[2];
};
#define MESHDEV_D2_BINARY(op)                      \
  inline D2 operator op(D2 a, D2 b) {              \
    return {{a.v[0] op b.v[0], a.v[1] op b.v[1]}}; \
  }
MESHDEV_D2_BINARY(+)
MESHDEV_D2_BINARY(-)
MESHDEV_D2_BINARY(*)
MESHDEV_D2_BINARY(/)
#undef MESHDEV_D2_BINARY
inline D2 sqrt(D2 a) {
  return {{std::sqrt(a.v[0]), std::sqrt(a.v[1])}};
}
inline M2 positive(D2 a) {
  return {{a.v[0] > 0.0, a.v[1] > 0.0}};
}
inline M2 zero(D2 a) {
  return {{a.v[0] == 0.0, a.v[1] == 0.0}};
}
inline M2 operator&(M2 a, M2 b) {
  return {{a.v[0] && b.v[0], a.v[1] && b.v[1]}};
}
inline M2 operator|(M2 a, M2 b) {
  return {{a.v[0] || b.v[0], a.v[1] || b.v[1]}};
}
inline D2 keep(M2 m, D2 a) {
  return {{m.v[0] ? a.v[0] : 0.0, m.v[1] ? a.v[1] : 0.0}};
}
inline int bits(M2 m) {
  return (m.v[0] ? 1 : 0) | (m.v[1] ? 2 : 0);
}
inline void store(double out[2], D2 a) {
  out[0] = a.v[0];
  out[1] = a.v[1];
}

#endif

}  // namespace meshdev::simd
