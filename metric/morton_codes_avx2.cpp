// morton_codes_avx2: MortonGrid::code for four points at once in AVX2 lanes. This translation
// unit alone is compiled with -mavx2 (metric/CMakeLists.txt) and is entered only after
// morton_order checked the CPU (simd_level()), so it uses intrinsics and plain code only: no
// inline function shared with other translation units, whose AVX2 copy the linker could pick
// for everyone.
#include <immintrin.h>

#include "metric/morton_order.h"

namespace meshdev::detail {
namespace {

// MortonGrid::cell for four coordinates: (x - x0) scale, NaN and negatives to 0 (max returns its
// second operand, 0, where t is NaN, and for -0), at most kMaxCell, truncated: the scalar
// version's cell for every double. As 64-bit lanes.
inline __attribute__((always_inline)) __m256i cells4(__m256d x, __m256d x0, __m256d scale,
                                                     __m256d max_cell) {
  const __m256d t = _mm256_mul_pd(_mm256_sub_pd(x, x0), scale);
  const __m256d clamped = _mm256_min_pd(_mm256_max_pd(t, _mm256_setzero_pd()), max_cell);
  return _mm256_cvtepu32_epi64(_mm256_cvttpd_epi32(clamped));
}

// The low 21 bits of each lane spread to every third bit (bit k -> bit 3k).
inline __attribute__((always_inline)) __m256i spread21x4(__m256i x) {
  x = _mm256_and_si256(_mm256_or_si256(x, _mm256_slli_epi64(x, 32)),
                       _mm256_set1_epi64x(0x1f00000000ffffLL));
  x = _mm256_and_si256(_mm256_or_si256(x, _mm256_slli_epi64(x, 16)),
                       _mm256_set1_epi64x(0x1f0000ff0000ffLL));
  x = _mm256_and_si256(_mm256_or_si256(x, _mm256_slli_epi64(x, 8)),
                       _mm256_set1_epi64x(0x100f00f00f00f00fLL));
  x = _mm256_and_si256(_mm256_or_si256(x, _mm256_slli_epi64(x, 4)),
                       _mm256_set1_epi64x(0x10c30c30c30c30c3LL));
  return _mm256_and_si256(_mm256_or_si256(x, _mm256_slli_epi64(x, 2)),
                          _mm256_set1_epi64x(0x1249249249249249LL));
}

}  // namespace

MortonRun morton_codes_avx2(const Vec3* points, std::size_t n, const double origin[3], double scale,
                            std::uint32_t max_cell, std::uint64_t* codes) {
  const __m256d x0 = _mm256_set1_pd(origin[0]), y0 = _mm256_set1_pd(origin[1]),
                z0 = _mm256_set1_pd(origin[2]);
  const __m256d s = _mm256_set1_pd(scale), top = _mm256_set1_pd(static_cast<double>(max_cell));
  auto codes4 = [&](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const __m256d x = _mm256_set_pd(d.x, c.x, b.x, a.x);
    const __m256d y = _mm256_set_pd(d.y, c.y, b.y, a.y);
    const __m256d z = _mm256_set_pd(d.z, c.z, b.z, a.z);
    return _mm256_or_si256(_mm256_or_si256(spread21x4(cells4(x, x0, s, top)),
                                           _mm256_slli_epi64(spread21x4(cells4(y, y0, s, top)), 1)),
                           _mm256_slli_epi64(spread21x4(cells4(z, z0, s, top)), 2));
  };
  // Codes are below 2^63, so the signed comparisons order them as unsigned.
  __m256i least = _mm256_set1_epi64x(0x7fffffffffffffffLL), most = _mm256_setzero_si256();
  __m256i descents = _mm256_setzero_si256();  // per lane: -1 per code below the one before
  __m256i before = _mm256_setzero_si256();    // the four codes before (lane 3: the last one)
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const Vec3* p = points + i;
    const __m256i code = codes4(p[0], p[1], p[2], p[3]);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(codes + i), code);
    // Each lane's predecessor: lanes 0-2 of this group moved up one, lane 3 of the group before.
    const __m256i previous = _mm256_blend_epi32(_mm256_permute4x64_epi64(code, 0x90),
                                                _mm256_permute4x64_epi64(before, 0xff), 0x03);
    // (The first point's "predecessor", 0, is never above it.)
    descents = _mm256_add_epi64(descents, _mm256_cmpgt_epi64(previous, code));
    least = _mm256_blendv_epi8(least, code, _mm256_cmpgt_epi64(least, code));
    most = _mm256_blendv_epi8(most, code, _mm256_cmpgt_epi64(code, most));
    before = code;
  }
  alignas(32) std::uint64_t lanes[4];
  MortonRun run;
  if (i > 0) {  // the groups of four
    _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), descents);
    for (int k = 0; k < 4; ++k) run.descents += static_cast<std::size_t>(0 - lanes[k]);
    _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), least);
    for (int k = 0; k < 4; ++k) run.least = lanes[k] < run.least ? lanes[k] : run.least;
    _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), most);
    for (int k = 0; k < 4; ++k) run.most = lanes[k] > run.most ? lanes[k] : run.most;
  }
  if (i < n) {  // the last one to three points: the lanes past n repeat the last point
    const Vec3* p = points + i;
    const std::size_t k1 = i + 1 < n ? 1 : 0, k2 = i + 2 < n ? 2 : k1;
    std::uint64_t previous = 0;  // the code before lanes[k] (none for the first point)
    if (i > 0) {
      _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), before);
      previous = lanes[3];
    }
    _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), codes4(p[0], p[k1], p[k2], p[k2]));
    for (std::size_t k = 0; i + k < n; ++k) {
      const std::uint64_t code = lanes[k];
      codes[i + k] = code;
      run.descents += i + k > 0 && code < previous;
      previous = code;
      run.least = code < run.least ? code : run.least;
      run.most = code > run.most ? code : run.most;
    }
  }
  return run;
}

}  // namespace meshdev::detail
