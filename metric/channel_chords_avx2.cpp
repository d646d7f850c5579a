// channel_chords_x4 in AVX lanes. This translation unit alone is compiled with -mavx2 (and, as
// the whole library, -ffp-contract=off; metric/CMakeLists.txt) and is entered only after the
// caller checked the CPU (simd_level()), so it uses intrinsics and plain code only: no inline
// function shared with other translation units, whose AVX copy the linker could pick for
// everyone.
#include <immintrin.h>

#include "metric/channel_chords.h"

namespace meshdev::detail {
namespace {

// One mesh's side of four samples: their faces' corners and barycentrics, lane l for sample l.
struct Side {
  const std::uint32_t* corners[4];
  __m256d bary[3];
};

Side side_of(const ChordSample s[4], bool target) {
  Side side;
  double b[3][4];
  for (int l = 0; l < 4; ++l) {
    side.corners[l] = target ? s[l].tb : s[l].ta;
    const double* bary = target ? s[l].bary_b : s[l].bary_a;
    for (int c = 0; c < 3; ++c) b[c][l] = bary[c];
  }
  for (int c = 0; c < 3; ++c) side.bary[c] = _mm256_loadu_pd(b[c]);
  return side;
}

// Component k of per-vertex `values` (dim per vertex) at each lane's barycentrics of its face:
// (b0 v0 + b1 v1) + b2 v2, barycentric_mix's order.
inline __attribute__((always_inline)) __m256d mix4(const double* values, std::size_t dim,
                                                   const Side& side, std::size_t k) {
  __m256d sum = _mm256_setzero_pd();
  for (int c = 0; c < 3; ++c) {
    auto value = [&](int l) { return values[side.corners[l][c] * dim + k]; };
    const __m256d term =
        _mm256_mul_pd(side.bary[c], _mm256_set_pd(value(3), value(2), value(1), value(0)));
    sum = c == 0 ? term : _mm256_add_pd(sum, term);
  }
  return sum;
}

struct Vec4x3 {
  __m256d x, y, z;
};

// (x x' + y y') + z z', Vec3's dot.
inline __attribute__((always_inline)) __m256d dot4(const Vec4x3& a, const Vec4x3& b) {
  return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a.x, b.x), _mm256_mul_pd(a.y, b.y)),
                       _mm256_mul_pd(a.z, b.z));
}

// unit_normal per lane: (1 / |n|) n where |n| > 0, else 0.
inline __attribute__((always_inline)) Vec4x3 unit4(const Vec4x3& n) {
  const __m256d len = _mm256_sqrt_pd(dot4(n, n));
  const __m256d positive = _mm256_cmp_pd(len, _mm256_setzero_pd(), _CMP_GT_OQ);
  const __m256d inverse = _mm256_div_pd(_mm256_set1_pd(1.0), len);
  return {_mm256_and_pd(positive, _mm256_mul_pd(inverse, n.x)),
          _mm256_and_pd(positive, _mm256_mul_pd(inverse, n.y)),
          _mm256_and_pd(positive, _mm256_mul_pd(inverse, n.z))};
}

inline __attribute__((always_inline)) __m256d is_zero(const Vec4x3& n) {
  const __m256d zero = _mm256_setzero_pd();
  return _mm256_and_pd(
      _mm256_and_pd(_mm256_cmp_pd(n.x, zero, _CMP_EQ_OQ), _mm256_cmp_pd(n.y, zero, _CMP_EQ_OQ)),
      _mm256_cmp_pd(n.z, zero, _CMP_EQ_OQ));
}

}  // namespace

void channel_chords_x4(const ChordChannel* channels, std::size_t count, const ChordSample s[4],
                       ChannelChords* out) {
  const Side a = side_of(s, false), b = side_of(s, true);
  for (std::size_t j = 0; j < count; ++j) {
    const ChordChannel& ch = channels[j];
    ChannelChords& o = out[j];
    if (ch.unit_normals) {
      const Vec4x3 na = unit4(
          {mix4(ch.reference, 3, a, 0), mix4(ch.reference, 3, a, 1), mix4(ch.reference, 3, a, 2)});
      const Vec4x3 nb =
          unit4({mix4(ch.target, 3, b, 0), mix4(ch.target, 3, b, 1), mix4(ch.target, 3, b, 2)});
      const Vec4x3 difference{_mm256_sub_pd(na.x, nb.x), _mm256_sub_pd(na.y, nb.y),
                              _mm256_sub_pd(na.z, nb.z)};
      const Vec4x3 sum{_mm256_add_pd(na.x, nb.x), _mm256_add_pd(na.y, nb.y),
                       _mm256_add_pd(na.z, nb.z)};
      _mm256_storeu_pd(o.chord, _mm256_sqrt_pd(dot4(difference, difference)));
      _mm256_storeu_pd(o.across, _mm256_sqrt_pd(dot4(sum, sum)));
      o.either_zero = _mm256_movemask_pd(_mm256_or_pd(is_zero(na), is_zero(nb)));
      continue;
    }
    if (ch.dim < 1 || ch.dim > 3) continue;  // left to the caller
    const std::size_t dim = static_cast<std::size_t>(ch.dim);
    __m256d sum = _mm256_setzero_pd();  // the squared differences in component order
    for (std::size_t c = 0; c < dim; ++c) {
      const __m256d e = _mm256_sub_pd(mix4(ch.reference, dim, a, c), mix4(ch.target, dim, b, c));
      sum = _mm256_add_pd(sum, _mm256_mul_pd(e, e));
    }
    _mm256_storeu_pd(o.chord, _mm256_sqrt_pd(sum));
    o.either_zero = 0;
  }
}

}  // namespace meshdev::detail
