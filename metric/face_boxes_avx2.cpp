// face_boxes_avx2: face_boxes with four faces in the four double lanes of AVX registers. This
// translation unit alone is compiled with -mavx2 (no FMA; metric/CMakeLists.txt) and is entered
// only after the caller checked the CPU (simd_level()), so it uses intrinsics and plain code only:
// no inline function shared with other translation units, whose AVX2 copy the linker could pick
// for everyone. Each lane runs the baseline's operations (std::min and std::max as their
// comparisons choose, float_rounding.h's steps), so the records and bounds are the same bit for
// bit.
#include <immintrin.h>

#include <cfloat>
#include <cstddef>

#include "metric/face_boxes.h"

namespace meshdev::detail {
namespace {

// std::min(a, b) and std::max(a, b) lane by lane: b where b < a (a < b), else a.
__m256d min_as_std(__m256d a, __m256d b) {
  return _mm256_blendv_pd(a, b, _mm256_cmp_pd(b, a, _CMP_LT_OQ));
}
__m256d max_as_std(__m256d a, __m256d b) {
  return _mm256_blendv_pd(a, b, _mm256_cmp_pd(a, b, _CMP_LT_OQ));
}

// The 64-bit lane masks of a comparison as 32-bit lanes.
__m128i narrow(__m256d mask) {
  return _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(
      _mm256_castpd_si256(mask), _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6)));
}

// round_down_to_float, lane by lane: float to nearest, one step toward -inf where that went above
// x, then std::min with the largest float.
__m128 round_down(__m256d x) {
  const __m128 f = _mm256_cvtpd_ps(x);
  const __m128i bits = _mm_castps_si128(f);
  const __m128i above = narrow(_mm256_cmp_pd(_mm256_cvtps_pd(f), x, _CMP_GT_OQ));
  const __m128i step = _mm_sub_epi32(
      _mm_set1_epi32(-1), _mm_add_epi32(_mm_srai_epi32(bits, 31), _mm_srai_epi32(bits, 31)));
  const __m128 r = _mm_castsi128_ps(_mm_add_epi32(bits, _mm_and_si128(step, above)));
  const __m128 top = _mm_set1_ps(FLT_MAX);
  return _mm_blendv_ps(r, top, _mm_cmplt_ps(top, r));
}

// round_up_to_float, lane by lane: +inf for NaN; float to nearest, one step toward +inf where that
// went below x, then std::max with the least float.
__m128 round_up(__m256d x) {
  const __m128 f = _mm256_cvtpd_ps(x);
  const __m128i bits = _mm_castps_si128(f);
  const __m128i below = narrow(_mm256_cmp_pd(_mm256_cvtps_pd(f), x, _CMP_LT_OQ));
  const __m128i step = _mm_add_epi32(
      _mm_set1_epi32(1), _mm_add_epi32(_mm_srai_epi32(bits, 31), _mm_srai_epi32(bits, 31)));
  __m128 r = _mm_castsi128_ps(_mm_add_epi32(bits, _mm_and_si128(step, below)));
  const __m128 bottom = _mm_set1_ps(-FLT_MAX);
  r = _mm_blendv_ps(r, bottom, _mm_cmplt_ps(r, bottom));
  const __m128 nan = _mm_castsi128_ps(narrow(_mm256_cmp_pd(x, x, _CMP_UNORD_Q)));
  return _mm_blendv_ps(r, _mm_set1_ps(__builtin_inff()), nan);
}

}  // namespace

void face_boxes_avx2(const double* positions, const std::uint32_t* corners, std::uint32_t begin,
                     std::uint32_t end, const FrameMap& frame, FaceBox* out, LaneBounds& boxes,
                     LaneBounds& centres, CornerBounds& corner_bounds) {
  constexpr std::uint32_t kAhead = 8;  // as face_boxes
  __m128 box_lo = _mm_load_ps(boxes.lo), box_hi = _mm_load_ps(boxes.hi);
  __m128 centre_lo = _mm_load_ps(centres.lo), centre_hi = _mm_load_ps(centres.hi);
  const __m256d origin[3] = {_mm256_set1_pd(frame.origin[0]), _mm256_set1_pd(frame.origin[1]),
                             _mm256_set1_pd(frame.origin[2])};
  const __m256d scale = _mm256_set1_pd(frame.scale);
  // The corners' own coordinates: min_pd / max_pd keep the second operand where the first is
  // NaN or both are equal, as BoundingBox::extend keeps its bound.
  __m256d corner_lo[3], corner_hi[3];
  for (int k = 0; k < 3; ++k) {
    corner_lo[k] = _mm256_set1_pd(corner_bounds.lo[k]);
    corner_hi[k] = _mm256_set1_pd(corner_bounds.hi[k]);
  }
  std::uint32_t f = begin;
  for (; f + 4 <= end; f += 4) {
    const std::uint32_t* ids = corners + 3 * std::size_t{f};
    if (f + kAhead + 4 <= end)
      for (int k = 0; k < 12; ++k)
        __builtin_prefetch(positions + 3 * std::size_t{ids[3 * kAhead + k]});
    __m256d lo[3], hi[3];
    for (int corner = 0; corner < 3; ++corner) {
      const double* p[4];
      for (int lane = 0; lane < 4; ++lane)
        p[lane] = positions + 3 * std::size_t{ids[3 * lane + corner]};
      for (int k = 0; k < 3; ++k) {
        const __m256d v = _mm256_setr_pd(p[0][k], p[1][k], p[2][k], p[3][k]);
        corner_lo[k] = _mm256_min_pd(v, corner_lo[k]);
        corner_hi[k] = _mm256_max_pd(v, corner_hi[k]);
        const __m256d x = _mm256_mul_pd(_mm256_sub_pd(v, origin[k]), scale);
        lo[k] = corner == 0 ? x : min_as_std(lo[k], x);
        hi[k] = corner == 0 ? x : max_as_std(hi[k], x);
      }
    }
    __m128 l0 = round_down(lo[0]), l1 = round_down(lo[1]), l2 = round_down(lo[2]);
    __m128 l3 = _mm_castsi128_ps(
        _mm_add_epi32(_mm_set1_epi32(static_cast<int>(f)), _mm_setr_epi32(0, 1, 2, 3)));
    __m128 h0 = round_up(hi[0]), h1 = round_up(hi[1]), h2 = round_up(hi[2]), h3 = _mm_setzero_ps();
    _MM_TRANSPOSE4_PS(l0, l1, l2, l3);  // row j: face f + j's lo, with its index's bits
    _MM_TRANSPOSE4_PS(h0, h1, h2, h3);
    const __m128 face_lo[4] = {l0, l1, l2, l3}, face_hi[4] = {h0, h1, h2, h3};
    FaceBox* box = out + (f - begin);
    for (int j = 0; j < 4; ++j) {
      _mm_store_ps(box[j].lo, face_lo[j]);
      _mm_store_ps(box[j].hi, face_hi[j]);
      const __m128 c = _mm_add_ps(face_lo[j], face_hi[j]);
      box_lo = _mm_min_ps(box_lo, face_lo[j]);
      box_hi = _mm_max_ps(box_hi, face_hi[j]);
      centre_lo = _mm_min_ps(centre_lo, c);
      centre_hi = _mm_max_ps(centre_hi, c);
    }
  }
  _mm_store_ps(boxes.lo, box_lo);
  _mm_store_ps(boxes.hi, box_hi);
  _mm_store_ps(centres.lo, centre_lo);
  _mm_store_ps(centres.hi, centre_hi);
  for (int k = 0; k < 3; ++k) {
    alignas(32) double lanes_lo[4], lanes_hi[4];
    _mm256_store_pd(lanes_lo, corner_lo[k]);
    _mm256_store_pd(lanes_hi, corner_hi[k]);
    for (int lane = 0; lane < 4; ++lane) {
      if (lanes_lo[lane] < corner_bounds.lo[k]) corner_bounds.lo[k] = lanes_lo[lane];
      if (lanes_hi[lane] > corner_bounds.hi[k]) corner_bounds.hi[k] = lanes_hi[lane];
    }
  }
  // The last faces (fewer than four) one at a time: the baseline's own code (not inline, so not
  // compiled here).
  if (f < end)
    face_boxes(positions, corners, f, end, frame, out + (f - begin), boxes, centres, corner_bounds);
}

}  // namespace meshdev::detail
