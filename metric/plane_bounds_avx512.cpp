// The plane-bound kernels for AVX-512F: sixteen lanes. This translation unit alone is compiled
// with -mavx512f (metric/CMakeLists.txt) and is entered only after plane_bounds.cpp has checked
// the CPU, so it uses intrinsics and plain loops only: no inline function shared with other
// translation units, whose AVX-512 copy the linker could pick for everyone.
#include <immintrin.h>

#include "metric/plane_bounds.h"

namespace meshdev {
namespace {

// Each lane keeps its two smallest bounds for the runner-up, as bounds_avx2 does.
LeastBounds bounds_avx512(const float* rows, std::size_t stride, std::size_t count,
                          const float q[3], float* bound) {
  const __m512 px = _mm512_set1_ps(q[0]), py = _mm512_set1_ps(q[1]), pz = _mm512_set1_ps(q[2]);
  const __m512 zero = _mm512_setzero_ps();
  __m512 least = _mm512_set1_ps(__builtin_inff()), second = least;
  const std::size_t lanes = (count + 15) & ~std::size_t{15};
  for (std::size_t i = 0; i < lanes; i += 16) {
    auto plane = [&](int r) {  // (n.p - d) with one rounding per coordinate
      const float* p = rows + r * stride + i;
      const __m512 t = _mm512_fmsub_ps(_mm512_loadu_ps(p), px, _mm512_loadu_ps(p + 3 * stride));
      return _mm512_fmadd_ps(_mm512_loadu_ps(p + 2 * stride), pz,
                             _mm512_fmadd_ps(_mm512_loadu_ps(p + stride), py, t));
    };
    const __m512 h = plane(kNx);
    const __m512 o = _mm512_max_ps(
        _mm512_max_ps(_mm512_max_ps(plane(kM0x), plane(kM0x + 4)), plane(kM0x + 8)), zero);
    // NaN -> 0: max returns its second operand when either is NaN.
    const __m512 b2 = _mm512_max_ps(_mm512_fmadd_ps(h, h, _mm512_mul_ps(o, o)), zero);
    second = _mm512_min_ps(second, _mm512_max_ps(least, b2));
    least = _mm512_min_ps(b2, least);
    _mm512_storeu_ps(bound + i, b2);
  }
  const __m512 smallest = _mm512_set1_ps(_mm512_reduce_min_ps(least));
  // The first lane holding the smallest gives its second instead (bounds_avx2's runner_up_of).
  const unsigned at = _mm512_cmp_ps_mask(least, smallest, _CMP_EQ_OQ);
  const __mmask16 pick = static_cast<__mmask16>(at & (~at + 1u));
  const float runner_up = _mm512_reduce_min_ps(_mm512_mask_blend_ps(pick, least, second));
  for (std::size_t i = 0; i < lanes; i += 16) {
    const unsigned equal = _mm512_cmp_ps_mask(_mm512_loadu_ps(bound + i), smallest, _CMP_EQ_OQ);
    if (equal != 0) {
      const std::size_t first = i + static_cast<unsigned>(__builtin_ctz(equal));
      return {first < count ? first : 0, runner_up};
    }
  }
  return {0, runner_up};
}

std::size_t survivors_avx512(const float* bound, std::size_t count, float cutoff, std::size_t skip,
                             std::uint32_t* out) {
  const __m512 cut = _mm512_set1_ps(cutoff);
  std::size_t n = 0;
  const std::size_t lanes = (count + 15) & ~std::size_t{15};
  for (std::size_t i = 0; i < lanes; i += 16) {
    unsigned keep = _mm512_cmp_ps_mask(_mm512_loadu_ps(bound + i), cut, _CMP_NGT_UQ);
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
const PlaneKernels kPlaneKernelsAvx512{bounds_avx512, survivors_avx512, block_bounds_avx2,
                                       block_planes_avx2};
}  // namespace detail

}  // namespace meshdev
