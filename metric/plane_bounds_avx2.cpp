// The plane-bound kernels for AVX2 + FMA: eight lanes. This translation unit alone is compiled
// with -mavx2 -mfma (metric/CMakeLists.txt) and is entered only after plane_bounds.cpp has
// checked the CPU, so it uses intrinsics and plain loops only: no inline function shared with
// other translation units, whose AVX2 copy the linker could pick for everyone.
#include <immintrin.h>

#include "metric/plane_bounds.h"

namespace meshdev {
namespace {

// The smallest of four lanes, in every lane.
__m128 broadcast_min4(__m128 v) {
  __m128 m = _mm_min_ps(v, _mm_movehl_ps(v, v));
  m = _mm_min_ss(m, _mm_shuffle_ps(m, m, 1));
  return _mm_shuffle_ps(m, m, 0);
}
// The smallest of eight lanes, in every lane: the two halves' minima, then as above.
__m256 broadcast_min(__m256 v) {
  return _mm256_broadcastss_ps(
      broadcast_min4(_mm_min_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1))));
}
// The least of four unsigned lanes.
std::size_t least_index4(__m128i at) {
  at = _mm_min_epu32(at, _mm_shuffle_epi32(at, 0x4e));
  at = _mm_min_epu32(at, _mm_shuffle_epi32(at, 0xb1));
  return static_cast<std::size_t>(_mm_cvtsi128_si32(at));
}

// The runner-up of bounds whose lanes kept their two smallest (least <= second, lane by lane):
// the first lane whose least is `smallest` gives its second instead, then the least of all
// lanes (so two equal smallest bounds give smallest). Eight lanes, then four.
float runner_up_of(__m256 least, __m256 second, __m256 smallest) {
  const unsigned equal =
      static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(least, smallest, _CMP_EQ_OQ)));
  const int lane = equal != 0 ? __builtin_ctz(equal) : -1;  // -1: none (no lane given up)
  const __m256 pick = _mm256_castsi256_ps(
      _mm256_cmpeq_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), _mm256_set1_epi32(lane)));
  return _mm256_cvtss_f32(broadcast_min(_mm256_blendv_ps(least, second, pick)));
}
float runner_up_of4(__m128 least, __m128 second, __m128 smallest) {
  const unsigned equal = static_cast<unsigned>(_mm_movemask_ps(_mm_cmpeq_ps(least, smallest)));
  const int lane = equal != 0 ? __builtin_ctz(equal) : -1;
  const __m128 pick =
      _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_setr_epi32(0, 1, 2, 3), _mm_set1_epi32(lane)));
  return _mm_cvtss_f32(broadcast_min4(_mm_blendv_ps(least, second, pick)));
}

// The index of the smallest bound, the first of equal ones: each lane tracked the index of its
// first least bound (least_at), and the least of those indices among the lanes whose least is the
// smallest is the first overall. Without a loop or a branch on the bounds. Eight lanes (the two
// halves' minima first), then four.
std::size_t first_of(__m256 least, __m256i least_at, __m256 smallest) {
  const __m256i equal = _mm256_castps_si256(_mm256_cmp_ps(least, smallest, _CMP_EQ_OQ));
  const __m256i at = _mm256_blendv_epi8(_mm256_set1_epi32(0x7fffffff), least_at, equal);
  return least_index4(_mm_min_epu32(_mm256_castsi256_si128(at), _mm256_extracti128_si256(at, 1)));
}
std::size_t first_of4(__m128 least, __m128i least_at, __m128 smallest) {
  const __m128i equal = _mm_castps_si128(_mm_cmpeq_ps(least, smallest));
  return least_index4(_mm_blendv_epi8(_mm_set1_epi32(0x7fffffff), least_at, equal));
}

// Each lane keeps its two smallest bounds (second = min(second, max(least, b)) before least =
// min(least, b)) for the runner-up.
LeastBounds bounds_avx2(const float* rows, std::size_t stride, std::size_t count, const float q[3],
                        float* bound) {
  const __m256 px = _mm256_set1_ps(q[0]), py = _mm256_set1_ps(q[1]), pz = _mm256_set1_ps(q[2]);
  const __m256 zero = _mm256_setzero_ps();
  __m256 least = _mm256_set1_ps(__builtin_inff()), second = least;
  __m256i least_at = _mm256_setzero_si256(), at = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const std::size_t lanes = (count + 7) & ~std::size_t{7};
  for (std::size_t i = 0; i < lanes; i += 8) {
    auto plane = [&](int r) {  // (n.p - d) with one rounding per coordinate
      const float* p = rows + r * stride + i;
      const __m256 t = _mm256_fmsub_ps(_mm256_loadu_ps(p), px, _mm256_loadu_ps(p + 3 * stride));
      return _mm256_fmadd_ps(_mm256_loadu_ps(p + 2 * stride), pz,
                             _mm256_fmadd_ps(_mm256_loadu_ps(p + stride), py, t));
    };
    const __m256 h = plane(kNx);
    const __m256 o = _mm256_max_ps(
        _mm256_max_ps(_mm256_max_ps(plane(kM0x), plane(kM0x + 4)), plane(kM0x + 8)), zero);
    // NaN -> 0: max returns its second operand when either is NaN.
    const __m256 b2 = _mm256_max_ps(_mm256_fmadd_ps(h, h, _mm256_mul_ps(o, o)), zero);
    second = _mm256_min_ps(second, _mm256_max_ps(least, b2));
    least_at =
        _mm256_blendv_epi8(least_at, at, _mm256_castps_si256(_mm256_cmp_ps(b2, least, _CMP_LT_OQ)));
    at = _mm256_add_epi32(at, _mm256_set1_epi32(8));
    least = _mm256_min_ps(b2, least);
    _mm256_storeu_ps(bound + i, b2);
  }
  const __m256 smallest = broadcast_min(least);
  const float runner_up = runner_up_of(least, second, smallest);
  return {first_of(least, least_at, smallest), runner_up};
}

std::size_t survivors_avx2(const float* bound, std::size_t count, float cutoff, std::size_t skip,
                           std::uint32_t* out) {
  const __m256 cut = _mm256_set1_ps(cutoff);
  std::size_t n = 0;
  const std::size_t lanes = (count + 7) & ~std::size_t{7};
  for (std::size_t i = 0; i < lanes; i += 8) {
    unsigned keep = static_cast<unsigned>(
        _mm256_movemask_ps(_mm256_cmp_ps(_mm256_loadu_ps(bound + i), cut, _CMP_NGT_UQ)));
    while (keep != 0) {
      const std::size_t idx = i + static_cast<unsigned>(__builtin_ctz(keep));
      keep &= keep - 1;
      if (idx != skip && idx < count) out[n++] = static_cast<std::uint32_t>(idx);
    }
  }
  return n;
}

}  // namespace

namespace detail {

// One block per step in four lanes, with bounds_avx2's operations in its order (the same bits).
// Before, two blocks shared an eight-lane step, whose upper half took a load and an insertion per
// row, and an odd last block took a whole step: `peer_compare A B 1000000 --ab 8|12`, 1 / 2
// threads, torus100k -> 1m 1.011 / 1.014, 1.031 / 1.013 and 1.021 / 1.021; torus100k -> 10k
// 1.002 / 1.005, buildings_s40k -> buildings 0.995 / 1.000, torus100k -> torus1m_shuffled
// 1.004 / 1.007, armadillo 1.003 / 1.006 (docs/performance-log.md §3, forty-sixth session).
LeastBounds block_bounds_avx2(const BlockPlanes* const* blocks, const std::uint8_t* which,
                              std::size_t count, const float q[3], float* bound) {
  const __m128 px = _mm_set1_ps(q[0]), py = _mm_set1_ps(q[1]), pz = _mm_set1_ps(q[2]);
  const __m128 zero = _mm_setzero_ps();
  __m128 least = _mm_set1_ps(__builtin_inff()), second = least;
  __m128i least_at = _mm_setzero_si128(), at = _mm_setr_epi32(0, 1, 2, 3);
  for (std::size_t j = 0; j < count; ++j) {
    const BlockPlanes& a = *blocks[which[j]];
    auto plane = [&](int r) {  // (n.p - d) with one rounding per coordinate
      const __m128 t = _mm_fmsub_ps(_mm_load_ps(a.row[r]), px, _mm_load_ps(a.row[r + 3]));
      return _mm_fmadd_ps(_mm_load_ps(a.row[r + 2]), pz,
                          _mm_fmadd_ps(_mm_load_ps(a.row[r + 1]), py, t));
    };
    const __m128 h = plane(kNx);
    const __m128 o =
        _mm_max_ps(_mm_max_ps(_mm_max_ps(plane(kM0x), plane(kM0x + 4)), plane(kM0x + 8)), zero);
    // NaN -> 0: max returns its second operand when either is NaN.
    const __m128 b2 = _mm_max_ps(_mm_fmadd_ps(h, h, _mm_mul_ps(o, o)), zero);
    _mm_storeu_ps(bound + 4 * j, b2);
    second = _mm_min_ps(second, _mm_max_ps(least, b2));
    least_at = _mm_blendv_epi8(least_at, at, _mm_castps_si128(_mm_cmplt_ps(b2, least)));
    at = _mm_add_epi32(at, _mm_set1_epi32(4));
    least = _mm_min_ps(b2, least);
  }
  const __m128 smallest = broadcast_min4(least);
  return {first_of4(least, least_at, smallest), runner_up_of4(least, second, smallest)};
}

}  // namespace detail

namespace {

// Four doubles per register: the lanes of a block at once.
struct D3 {
  __m256d x, y, z;
};
inline D3 sub(const D3& a, const D3& b) {
  return {_mm256_sub_pd(a.x, b.x), _mm256_sub_pd(a.y, b.y), _mm256_sub_pd(a.z, b.z)};
}
inline D3 scale(const D3& a, __m256d s) {
  return {_mm256_mul_pd(a.x, s), _mm256_mul_pd(a.y, s), _mm256_mul_pd(a.z, s)};
}
inline __m256d dot(const D3& a, const D3& b) {
  return _mm256_fmadd_pd(a.z, b.z, _mm256_fmadd_pd(a.y, b.y, _mm256_mul_pd(a.x, b.x)));
}
inline D3 cross(const D3& a, const D3& b) {
  return {_mm256_fmsub_pd(a.y, b.z, _mm256_mul_pd(a.z, b.y)),
          _mm256_fmsub_pd(a.z, b.x, _mm256_mul_pd(a.x, b.z)),
          _mm256_fmsub_pd(a.x, b.y, _mm256_mul_pd(a.y, b.x))};
}
// Rounded to float; lanes outside `keep` are 0.
inline void put(float* out, __m256d v, __m256d keep) {
  _mm_storeu_ps(out, _mm256_cvtpd_ps(_mm256_and_pd(v, keep)));
}

}  // namespace

namespace detail {

void block_planes_avx2(const float corner[3][3][4], BlockPlanes& out) {
  D3 v[3];
  for (int c = 0; c < 3; ++c)
    v[c] = {_mm256_cvtps_pd(_mm_loadu_ps(corner[c][0])),
            _mm256_cvtps_pd(_mm_loadu_ps(corner[c][1])),
            _mm256_cvtps_pd(_mm_loadu_ps(corner[c][2]))};
  const D3 ab = sub(v[1], v[0]), ac = sub(v[2], v[0]);
  const D3 n = cross(ab, ac);
  const __m256d n2 = dot(n, n);
  // kappa <= kMaxCullKappa, squared, and |n|^2 >= kMinCullNormal2 (false for NaN).
  const __m256d keep = _mm256_and_pd(
      _mm256_cmp_pd(n2, _mm256_set1_pd(kMinCullNormal2), _CMP_GE_OQ),
      _mm256_cmp_pd(_mm256_mul_pd(dot(ab, ab), dot(ac, ac)),
                    _mm256_mul_pd(_mm256_set1_pd(kMaxCullKappa * kMaxCullKappa), n2), _CMP_LE_OQ));
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d sign = _mm256_set1_pd(-0.0);
  // The edge normals from n itself (e x n, made unit), not from the unit normal: the four
  // square roots and divisions do not wait for each other (chunk-interleaved, 1 and 2 threads:
  // torus100k -> 1m +1.0 / +1.7 %, torus1m -> 100k +0.6 %; docs/performance-log.md §3).
  D3 edge_normal[3];
  __m256d edge_scale[3];
  for (int e = 0; e < 3; ++e) {
    edge_normal[e] = cross(sub(v[(e + 1) % 3], v[e]), n);
    edge_scale[e] = _mm256_div_pd(one, _mm256_sqrt_pd(dot(edge_normal[e], edge_normal[e])));
  }
  const D3 unit = scale(n, _mm256_div_pd(one, _mm256_sqrt_pd(n2)));
  const __m256d d = dot(unit, v[0]);
  __m256d max_offset = _mm256_andnot_pd(sign, d);
  put(out.row[kNx], unit.x, keep);
  put(out.row[kNy], unit.y, keep);
  put(out.row[kNz], unit.z, keep);
  put(out.row[kD], d, keep);
  for (int e = 0; e < 3; ++e) {
    const D3 m = scale(edge_normal[e], edge_scale[e]);
    const __m256d md = dot(m, v[e]);
    put(out.row[kM0x + 4 * e], m.x, keep);
    put(out.row[kM0y + 4 * e], m.y, keep);
    put(out.row[kM0z + 4 * e], m.z, keep);
    put(out.row[kMd0 + 4 * e], md, keep);
    max_offset = _mm256_max_pd(max_offset, _mm256_andnot_pd(sign, md));
  }
  // Rounded up: one float step up where rounding to nearest went below (>= 0, so +1 on the bits).
  max_offset = _mm256_and_pd(max_offset, keep);
  const __m128 f = _mm256_cvtpd_ps(max_offset);
  const __m256i below64 =
      _mm256_castpd_si256(_mm256_cmp_pd(_mm256_cvtps_pd(f), max_offset, _CMP_LT_OQ));
  const __m128i below = _mm256_castsi256_si128(  // each lane's low half: 0 or -1
      _mm256_permutevar8x32_epi32(below64, _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6)));
  _mm_storeu_ps(out.max_offset, _mm_castsi128_ps(_mm_sub_epi32(_mm_castps_si128(f), below)));
}

const PlaneKernels kPlaneKernelsAvx2{bounds_avx2, survivors_avx2, block_bounds_avx2,
                                     block_planes_avx2};

}  // namespace detail

}  // namespace meshdev
