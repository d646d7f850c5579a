// centre_bins_avx2: centre_bins with four faces in the four double lanes of AVX registers. This
// translation unit alone is compiled with -mavx2 (no FMA; metric/CMakeLists.txt) and is entered
// only after the caller checked the CPU (simd_level()), so it uses intrinsics and plain code only:
// no inline function shared with other translation units, whose AVX2 copy the linker could pick
// for everyone. Each lane runs the baseline's operations (the float key, then the difference and
// product in double), so the bins are the same.
#include <immintrin.h>

#include <cassert>
#include <cstring>

#include "metric/centre_bins.h"

namespace meshdev::detail {
namespace {

template <int kAxis>
void bins_along(const FaceBox* boxes, std::uint32_t count, double lo, double scale, int bin_count,
                std::uint8_t* bins) {
  const __m256d lo4 = _mm256_set1_pd(lo), scale4 = _mm256_set1_pd(scale);
  const __m256d top4 = _mm256_set1_pd(bin_count - 1), zero = _mm256_setzero_pd();
  // The low byte of each 32-bit lane, in lane order, in the low four bytes.
  const __m128i low_bytes =
      _mm_setr_epi8(0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1);
  std::uint32_t i = 0;
  for (; i + 4 <= count; i += 4) {
    __m128 c[4];  // twice each box's centre, lanes x, y, z (and lane 3, never read)
    for (int k = 0; k < 4; ++k)
      c[k] = _mm_add_ps(_mm_load_ps(boxes[i + k].lo), _mm_load_ps(boxes[i + k].hi));
    __m128 key;  // the four faces' keys along kAxis
    if (kAxis == 0)
      key = _mm_movelh_ps(_mm_unpacklo_ps(c[0], c[1]), _mm_unpacklo_ps(c[2], c[3]));
    else if (kAxis == 1)
      key = _mm_movehl_ps(_mm_unpacklo_ps(c[2], c[3]), _mm_unpacklo_ps(c[0], c[1]));
    else
      key = _mm_movelh_ps(_mm_unpackhi_ps(c[0], c[1]), _mm_unpackhi_ps(c[2], c[3]));
    key = _mm_and_ps(key, _mm_cmpord_ps(key, key));  // NaN: +0
    __m256d t = _mm256_mul_pd(_mm256_sub_pd(_mm256_cvtps_pd(key), lo4), scale4);
    t = _mm256_and_pd(t, _mm256_cmp_pd(t, zero, _CMP_GT_OQ));  // t <= 0 or NaN: +0
    t = _mm256_min_pd(t, top4);                                // (t is not NaN here)
    const __m128i b = _mm_shuffle_epi8(_mm256_cvttpd_epi32(t), low_bytes);
    const int packed = _mm_cvtsi128_si32(b);
    std::memcpy(bins + i, &packed, 4);
  }
  // The last count % 4 faces: the baseline (not inline, compiled without AVX2).
  centre_bins(boxes + i, count - i, kAxis, lo, scale, bin_count, bins + i);
}

}  // namespace

void centre_bins_avx2(const FaceBox* boxes, std::uint32_t count, int axis, double lo, double scale,
                      int bin_count, std::uint8_t* bins) {
  assert(axis >= 0 && axis < 3 && bin_count >= 1 && bin_count <= 256);
  if (axis == 0)
    bins_along<0>(boxes, count, lo, scale, bin_count, bins);
  else if (axis == 1)
    bins_along<1>(boxes, count, lo, scale, bin_count, bins);
  else
    bins_along<2>(boxes, count, lo, scale, bin_count, bins);
}

}  // namespace meshdev::detail
