#include "metric/plane_bounds.h"

#include <cstdlib>
#include <limits>
#include <string>

#include "metric/errors.h"
#include "metric/simd4.h"

namespace meshdev {
namespace {

using simd::F4;

// The baseline kernels: four lanes (SSE2 on x86-64, plain C++ elsewhere), multiply then add.
std::size_t bounds_baseline(const float* rows, std::size_t stride, std::size_t count,
                            const float q[3], float* bound) {
  const F4 px = F4::splat(q[0]), py = F4::splat(q[1]), pz = F4::splat(q[2]);
  const F4 zero = F4::splat(0.0f);
  F4 least = F4::splat(std::numeric_limits<float>::infinity());
  const std::size_t lanes = (count + 3) & ~std::size_t{3};
  for (std::size_t i = 0; i < lanes; i += 4) {
    auto plane = [&](int r) {  // row r..r+2: a unit normal, r+3: its offset
      const float* p = rows + r * stride + i;
      return F4::load(p) * px + F4::load(p + stride) * py + F4::load(p + 2 * stride) * pz -
             F4::load(p + 3 * stride);
    };
    const F4 h = plane(kNx);
    const F4 o = max(max(max(plane(kM0x), plane(kM0x + 4)), plane(kM0x + 8)), zero);
    const F4 b2 = max(h * h + o * o, zero);  // NaN -> 0 (max returns its second operand)
    least = min(b2, least);
    simd::store(bound + i, b2);
  }
  float each[4];
  simd::store(each, least);
  float smallest = each[0];
  for (int k = 1; k < 4; ++k) smallest = each[k] < smallest ? each[k] : smallest;
  for (std::size_t i = 0; i < lanes; i += 4) {
    const int equal = simd::equal_mask(F4::load(bound + i), F4::splat(smallest));
    if (equal != 0) {
      const std::size_t first =
          i + static_cast<std::size_t>(__builtin_ctz(static_cast<unsigned>(equal)));
      return first < count ? first : 0;
    }
  }
  return 0;
}

std::size_t survivors_baseline(const float* bound, std::size_t count, float cutoff,
                               std::size_t skip, std::uint32_t* out) {
  const F4 cut = F4::splat(cutoff);
  std::size_t n = 0;
  const std::size_t lanes = (count + 3) & ~std::size_t{3};
  for (std::size_t i = 0; i < lanes; i += 4) {
    int keep = ~simd::greater_mask(F4::load(bound + i), cut) & 0xf;
    while (keep != 0) {
      const std::size_t idx =
          i + static_cast<std::size_t>(__builtin_ctz(static_cast<unsigned>(keep)));
      keep &= keep - 1;
      if (idx != skip && idx < count) out[n++] = static_cast<std::uint32_t>(idx);
    }
  }
  return n;
}

const PlaneKernels kBaseline{bounds_baseline, survivors_baseline};

bool cpu_has(SimdLevel level) {
#if defined(MESHDEV_X86_KERNELS)
  // GCC's and Clang's checks include the OS's support for the wider registers (XGETBV).
  __builtin_cpu_init();
  switch (level) {
    case SimdLevel::kBaseline:
      return true;
    case SimdLevel::kAvx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    case SimdLevel::kAvx512:
      return __builtin_cpu_supports("avx512f");
  }
  return false;
#else
  return level == SimdLevel::kBaseline;
#endif
}

SimdLevel detect() {
  // AVX-512 is not the default: its sixteen lanes cut instructions but ran 5-8 % slower than
  // AVX2 on this project's benchmark machine (docs/performance.md, "Run-time dispatch").
  const SimdLevel best = cpu_has(SimdLevel::kAvx2) ? SimdLevel::kAvx2 : SimdLevel::kBaseline;
  const char* env = std::getenv("MESHDEV_SIMD");
  if (env == nullptr || *env == '\0') return best;
  const std::string want(env);
  if (want == "baseline") return SimdLevel::kBaseline;
  if (want == "avx2") return best;
  if (want == "avx512") return cpu_has(SimdLevel::kAvx512) ? SimdLevel::kAvx512 : best;
  throw InvalidInput("MESHDEV_SIMD='" + want + "': expected baseline, avx2 or avx512");
}

}  // namespace

bool simd_supported(SimdLevel level) {
  return cpu_has(level);
}

SimdLevel simd_level() {
  static const SimdLevel level = detect();
  return level;
}

const char* simd_level_name(SimdLevel level) {
  switch (level) {
    case SimdLevel::kBaseline:
      return "baseline";
    case SimdLevel::kAvx2:
      return "avx2";
    case SimdLevel::kAvx512:
      return "avx512";
  }
  return "?";
}

const PlaneKernels& plane_kernels(SimdLevel level) {
#if defined(MESHDEV_X86_KERNELS)
  if (level == SimdLevel::kAvx2) return detail::kPlaneKernelsAvx2;
  if (level == SimdLevel::kAvx512) return detail::kPlaneKernelsAvx512;
#endif
  return kBaseline;
}

}  // namespace meshdev
