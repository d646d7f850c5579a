// fill_leaf_block_avx2: fill_leaf_block with the block's four faces in the four double lanes of
// AVX registers. This translation unit alone is compiled with -mavx2 (no FMA; metric/
// CMakeLists.txt) and is entered only after the caller checked the CPU (simd_level()), so it uses
// intrinsics and plain code only: no inline function shared with other translation units, whose
// AVX2 copy the linker could pick for everyone. Each lane runs the baseline's operations in its
// order (vec3.h's dot and cross, std::max's choice, round_up_to_float's step), so the blocks are
// the same bit for bit.
#include <immintrin.h>

#include <cassert>
#include <cstddef>
#include <limits>

#include "metric/leaf_blocks.h"

namespace meshdev::detail {
namespace {

// dot(v, v) as vec3.h computes it: (x x + y y) + z z.
__m256d squared_norm4(const __m256d v[3]) {
  return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(v[0], v[0]), _mm256_mul_pd(v[1], v[1])),
                       _mm256_mul_pd(v[2], v[2]));
}

}  // namespace

LeafBlockSums fill_leaf_block_avx2(const double* positions, const std::uint32_t* corners,
                                   const std::uint32_t* face_ids, std::uint32_t count,
                                   const FrameMap& frame, LeafBlock& out) {
  assert(count >= 1 && count <= 4);
  constexpr float kInf = std::numeric_limits<float>::infinity();
  constexpr std::uint32_t kNone = 0xffffffffu;  // kNoFace (metric/mesh.h)
  // Lanes from count on repeat lane 0's face: their values equal lane 0's, so they change no
  // maximum, and they are left out of the sum and zeroed in the block.
  const std::uint32_t* tri[4];  // the lanes' corner indices
  for (std::uint32_t lane = 0; lane < 4; ++lane)
    tri[lane] = corners + 3 * std::size_t{face_ids[lane < count ? lane : 0]};
  const __m128 used = _mm_castsi128_ps(
      _mm_cmpgt_epi32(_mm_set1_epi32(static_cast<int>(count)), _mm_setr_epi32(0, 1, 2, 3)));

  // Each corner's x, y, z in one masked load (the fourth lane neither read nor faulted), the four
  // lanes' loads then transposed: torus1m's build 1.087 / 1.091 faster on 1 / 2 threads than
  // with a gather per axis and corner, torus1m_shuffled 1.131 / 1.084, buildings 1.110 / 1.094
  // (`peer_compare A B 1000000 --ab 8 --ab-build`, the same blocks; docs/performance-log.md §3).
  const __m256i xyz = _mm256_setr_epi64x(-1, -1, -1, 0);
  __m256d c[3][3];  // the float corners, exactly, in double: [corner][axis]
  __m256d error2 = _mm256_setzero_pd();
  for (int corner = 0; corner < 3; ++corner) {
    __m256d p[4];
    for (int lane = 0; lane < 4; ++lane)
      p[lane] = _mm256_maskload_pd(positions + 3 * std::size_t{tri[lane][corner]}, xyz);
    const __m256d x01z01 = _mm256_unpacklo_pd(p[0], p[1]);
    const __m256d y01 = _mm256_unpackhi_pd(p[0], p[1]);
    const __m256d x23z23 = _mm256_unpacklo_pd(p[2], p[3]);
    const __m256d y23 = _mm256_unpackhi_pd(p[2], p[3]);
    const __m256d axis[3] = {_mm256_permute2f128_pd(x01z01, x23z23, 0x20),
                             _mm256_permute2f128_pd(y01, y23, 0x20),
                             _mm256_permute2f128_pd(x01z01, x23z23, 0x31)};
    __m256d err2 = _mm256_setzero_pd();
    for (int k = 0; k < 3; ++k) {
      const __m256d x = _mm256_mul_pd(_mm256_sub_pd(axis[k], _mm256_set1_pd(frame.origin[k])),
                                      _mm256_set1_pd(frame.scale));
      const __m128 r = _mm256_cvtpd_ps(x);  // to nearest, as static_cast<float>
      _mm_store_ps(out.corner[corner][k], _mm_and_ps(r, used));
      c[corner][k] = _mm256_cvtps_pd(r);
      const __m256d d = _mm256_sub_pd(c[corner][k], x);
      err2 = _mm256_add_pd(err2, _mm256_mul_pd(d, d));
    }
    error2 = _mm256_max_pd(err2, error2);  // NaN err2: error2 (the second operand), as std::max
  }

  __m256d ab[3], ac[3], bc[3];
  for (int k = 0; k < 3; ++k) {
    ab[k] = _mm256_sub_pd(c[1][k], c[0][k]);
    ac[k] = _mm256_sub_pd(c[2][k], c[0][k]);
    bc[k] = _mm256_sub_pd(c[2][k], c[1][k]);
  }
  const __m256d sab = squared_norm4(ab), sac = squared_norm4(ac), sbc = squared_norm4(bc);
  // std::max({sab, sac, sbc}): the first operand, replaced by each later one that it is less than.
  __m256d longest = _mm256_blendv_pd(sab, sac, _mm256_cmp_pd(sab, sac, _CMP_LT_OQ));
  longest = _mm256_blendv_pd(longest, sbc, _mm256_cmp_pd(longest, sbc, _CMP_LT_OQ));
  longest = _mm256_sqrt_pd(longest);

  // cross(ab, ac) as vec3.h computes it, then kappa = (|ab| |ac|) / |n|.
  const __m256d n[3] = {_mm256_sub_pd(_mm256_mul_pd(ab[1], ac[2]), _mm256_mul_pd(ab[2], ac[1])),
                        _mm256_sub_pd(_mm256_mul_pd(ab[2], ac[0]), _mm256_mul_pd(ab[0], ac[2])),
                        _mm256_sub_pd(_mm256_mul_pd(ab[0], ac[1]), _mm256_mul_pd(ab[1], ac[0]))};
  const __m256d n2 = squared_norm4(n);
  const __m256d kappa =
      _mm256_div_pd(_mm256_mul_pd(_mm256_sqrt_pd(sab), _mm256_sqrt_pd(sac)), _mm256_sqrt_pd(n2));
  // Culled by the bound: n2 >= kMinCullNormal2 and kappa <= kMaxCullKappa (false for NaN).
  const int culled = _mm256_movemask_pd(
      _mm256_and_pd(_mm256_cmp_pd(n2, _mm256_set1_pd(kMinCullNormal2), _CMP_GE_OQ),
                    _mm256_cmp_pd(kappa, _mm256_set1_pd(kMaxCullKappa), _CMP_LE_OQ)));
  // round_up_to_float of the margin, positive and far inside float's range where culled: float
  // to nearest, then one step up where that fell below.
  const __m256d margin = _mm256_mul_pd(_mm256_set1_pd(kMarginConstant * kFloatUnit),
                                       _mm256_add_pd(_mm256_set1_pd(2.0), kappa));
  const __m128 nearest = _mm256_cvtpd_ps(margin);
  const __m256d below = _mm256_and_pd(_mm256_cmp_pd(_mm256_cvtps_pd(nearest), margin, _CMP_LT_OQ),
                                      _mm256_set1_pd(1.0));
  const __m128 up = _mm_castsi128_ps(
      _mm_add_epi32(_mm_castps_si128(nearest), _mm_cvtps_epi32(_mm256_cvtpd_ps(below))));

  alignas(32) double edge[4], err[4];
  alignas(16) float up_lanes[4];
  _mm256_store_pd(edge, longest);
  _mm256_store_pd(err, error2);
  _mm_store_ps(up_lanes, up);
  LeafBlockSums sums;
  for (std::uint32_t lane = 0; lane < 4; ++lane) {
    const bool full = lane < count;
    out.face[lane] = full ? face_ids[lane] : kNone;
    out.margin[lane] = full && (culled >> lane & 1) ? up_lanes[lane] : kInf;
    if (full) sums.edge_sum += edge[lane];
    if (err[lane] > sums.corner_error2) sums.corner_error2 = err[lane];  // (no NaN lanes here)
  }
  return sums;
}

}  // namespace meshdev::detail
