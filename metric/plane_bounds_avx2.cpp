// The plane-bound kernels for AVX2 + FMA: eight lanes. This translation unit alone is compiled
// with -mavx2 -mfma (metric/CMakeLists.txt) and is entered only after plane_bounds.cpp has
// checked the CPU, so it uses intrinsics and plain loops only: no inline function shared with
// other translation units, whose AVX2 copy the linker could pick for everyone.
#include <immintrin.h>

#include "metric/plane_bounds.h"

namespace meshdev {
namespace {

std::size_t bounds_avx2(const float* rows, std::size_t stride, std::size_t count, const float q[3],
                        float* bound) {
  const __m256 px = _mm256_set1_ps(q[0]), py = _mm256_set1_ps(q[1]), pz = _mm256_set1_ps(q[2]);
  const __m256 zero = _mm256_setzero_ps();
  __m256 least = _mm256_set1_ps(__builtin_inff());
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
    least = _mm256_min_ps(b2, least);
    _mm256_storeu_ps(bound + i, b2);
  }
  __m128 m = _mm_min_ps(_mm256_castps256_ps128(least), _mm256_extractf128_ps(least, 1));
  m = _mm_min_ps(m, _mm_movehl_ps(m, m));
  m = _mm_min_ss(m, _mm_shuffle_ps(m, m, 1));
  const __m256 smallest = _mm256_broadcastss_ps(m);
  for (std::size_t i = 0; i < lanes; i += 8) {
    const int equal =
        _mm256_movemask_ps(_mm256_cmp_ps(_mm256_loadu_ps(bound + i), smallest, _CMP_EQ_OQ));
    if (equal != 0) {
      const std::size_t first =
          i + static_cast<unsigned>(__builtin_ctz(static_cast<unsigned>(equal)));
      return first < count ? first : 0;
    }
  }
  return 0;
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
const PlaneKernels kPlaneKernelsAvx2{bounds_avx2, survivors_avx2};
}  // namespace detail

}  // namespace meshdev
