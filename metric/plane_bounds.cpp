#include "metric/plane_bounds.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "metric/errors.h"
#include "metric/simd4.h"

namespace meshdev {
namespace {

using simd::F4;

constexpr float kInf = std::numeric_limits<float>::infinity();

// The runner-up of bounds whose lanes kept their two smallest (least <= second, lane by lane):
// the smallest of the other lanes' least and of the second of the first lane whose least is
// `smallest` (so two equal smallest bounds give smallest). O(1).
float runner_up_of(F4 least, F4 second, float smallest) {
  float l[4], s[4];
  simd::store(l, least);
  simd::store(s, second);
  bool taken = false;
  float r = kInf;
  for (int k = 0; k < 4; ++k) {
    float v = l[k];
    if (!taken && v == smallest) {
      v = s[k];
      taken = true;
    }
    r = v < r ? v : r;
  }
  return r;
}

// The baseline kernels: four lanes (SSE2 on x86-64, plain C++ elsewhere), multiply then add.
// Each lane keeps its two smallest bounds (second = min(second, max(least, b)) before least =
// min(least, b)) for the runner-up.
LeastBounds bounds_baseline(const float* rows, std::size_t stride, std::size_t count,
                            const float q[3], float* bound) {
  const F4 px = F4::splat(q[0]), py = F4::splat(q[1]), pz = F4::splat(q[2]);
  const F4 zero = F4::splat(0.0f);
  F4 least = F4::splat(kInf), second = least;
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
    second = min(second, max(least, b2));
    least = min(b2, least);
    simd::store(bound + i, b2);
  }
  float each[4];
  simd::store(each, least);
  float smallest = each[0];
  for (int k = 1; k < 4; ++k) smallest = each[k] < smallest ? each[k] : smallest;
  const float runner_up = runner_up_of(least, second, smallest);
  for (std::size_t i = 0; i < lanes; i += 4) {
    const int equal = simd::equal_mask(F4::load(bound + i), F4::splat(smallest));
    if (equal != 0) {
      const std::size_t first =
          i + static_cast<std::size_t>(__builtin_ctz(static_cast<unsigned>(equal)));
      return {first < count ? first : 0, runner_up};
    }
  }
  return {0, runner_up};
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

// bounds_baseline's arithmetic on each block's own rows, four lanes (one block) at a time.
LeastBounds block_bounds_baseline(const BlockPlanes* const* blocks, const std::uint8_t* which,
                                  std::size_t count, const float q[3], float* bound) {
  const F4 px = F4::splat(q[0]), py = F4::splat(q[1]), pz = F4::splat(q[2]);
  const F4 zero = F4::splat(0.0f);
  F4 least = F4::splat(kInf), second = least;
  for (std::size_t j = 0; j < count; ++j) {
    const BlockPlanes& b = *blocks[which[j]];
    auto plane = [&](int r) {  // row r..r+2: a unit normal, r+3: its offset
      return F4::load(b.row[r]) * px + F4::load(b.row[r + 1]) * py + F4::load(b.row[r + 2]) * pz -
             F4::load(b.row[r + 3]);
    };
    const F4 h = plane(kNx);
    const F4 o = max(max(max(plane(kM0x), plane(kM0x + 4)), plane(kM0x + 8)), zero);
    const F4 b2 = max(h * h + o * o, zero);  // NaN -> 0 (max returns its second operand)
    second = min(second, max(least, b2));
    least = min(b2, least);
    simd::store(bound + 4 * j, b2);
  }
  float each[4];
  simd::store(each, least);
  float smallest = each[0];
  for (int k = 1; k < 4; ++k) smallest = each[k] < smallest ? each[k] : smallest;
  const float runner_up = runner_up_of(least, second, smallest);
  for (std::size_t i = 0; i < 4 * count; ++i)
    if (bound[i] == smallest) return {i, runner_up};
  return {0, runner_up};
}

// Lane by lane, in double: the twin of the SIMD variants.
void block_planes_baseline(const float corner[3][3][4], BlockPlanes& out) {
  out = BlockPlanes{};
  for (int lane = 0; lane < 4; ++lane) {
    double v[3][3];
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a) v[c][a] = corner[c][a][lane];
    auto sub = [](const double* x, const double* y, double* out3) {
      for (int a = 0; a < 3; ++a) out3[a] = x[a] - y[a];
    };
    auto cross = [](const double* x, const double* y, double* out3) {
      out3[0] = x[1] * y[2] - x[2] * y[1];
      out3[1] = x[2] * y[0] - x[0] * y[2];
      out3[2] = x[0] * y[1] - x[1] * y[0];
    };
    auto dot = [](const double* x, const double* y) {
      return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    };
    double ab[3], ac[3], n[3];
    sub(v[1], v[0], ab);
    sub(v[2], v[0], ac);
    cross(ab, ac, n);
    const double n2 = dot(n, n);
    // kappa <= kMaxCullKappa, squared (false for NaN).
    if (!(n2 >= kMinCullNormal2 && dot(ab, ab) * dot(ac, ac) <= kMaxCullKappa * kMaxCullKappa * n2))
      continue;
    const double inv = 1.0 / std::sqrt(n2);
    double unit[3];
    for (int a = 0; a < 3; ++a) unit[a] = n[a] * inv;
    const double d = dot(unit, v[0]);
    double max_offset = std::fabs(d);
    for (int a = 0; a < 3; ++a) out.row[kNx + a][lane] = static_cast<float>(unit[a]);
    out.row[kD][lane] = static_cast<float>(d);
    for (int e = 0; e < 3; ++e) {
      double edge[3], m[3];
      sub(v[(e + 1) % 3], v[e], edge);
      cross(edge, n, m);  // e x n made unit: the same direction as e x unit
      const double inv_m = 1.0 / std::sqrt(dot(m, m));
      for (int a = 0; a < 3; ++a) m[a] *= inv_m;
      const double md = dot(m, v[e]);
      for (int a = 0; a < 3; ++a) out.row[kM0x + 4 * e + a][lane] = static_cast<float>(m[a]);
      out.row[kMd0 + 4 * e][lane] = static_cast<float>(md);
      max_offset = std::max(max_offset, std::fabs(md));
    }
    float f = static_cast<float>(max_offset);  // rounded up
    if (static_cast<double>(f) < max_offset)
      f = std::nextafter(f, std::numeric_limits<float>::infinity());
    out.max_offset[lane] = f;
  }
}

const PlaneKernels kBaseline{bounds_baseline, survivors_baseline, block_bounds_baseline,
                             block_planes_baseline};

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
  // AVX2 on this project's benchmark machine, and 0.5-4 % slower on a later Intel Xeon with
  // AVX-512-FP16 (docs/performance-log.md §3).
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
