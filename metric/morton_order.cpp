#include "metric/morton_order.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

#include "metric/plane_bounds.h"

namespace meshdev {

MortonGrid::MortonGrid(const BoundingBox& box) : min_(box.min) {
  if (box.empty()) return;
  const Vec3 extent = box.max - box.min;
  const double scale = kMaxCell / std::max({extent.x, extent.y, extent.z});
  if (scale > 0.0 && std::isfinite(scale)) scale_ = scale;  // else one point, or not finite
}

bool stable_bucket_order(const std::uint32_t* bucket, std::size_t n,
                         std::vector<std::uint32_t>& order) {
  assert(n < (std::size_t{1} << 32));
  order.clear();
  if (std::is_sorted(bucket, bucket + n)) return false;
  std::vector<std::uint32_t> start(MortonGrid::kBuckets + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++start[bucket[i] + 1];
  for (std::uint32_t b = 0; b < MortonGrid::kBuckets; ++b) start[b + 1] += start[b];
  order.resize(n);
  for (std::size_t i = 0; i < n; ++i) order[start[bucket[i]]++] = static_cast<std::uint32_t>(i);
  return true;
}

namespace detail {

MortonRun morton_codes(const MortonGrid& grid, const Vec3* points, std::size_t n,
                       std::uint64_t* codes) {
  MortonRun run;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t code = grid.code(points[i]);
    codes[i] = code;
    run.descents += i > 0 && code < codes[i - 1];
    run.least = std::min(run.least, code);
    run.most = std::max(run.most, code);
  }
  return run;
}

#if !defined(MESHDEV_X86_KERNELS)
MortonRun morton_codes_avx2(const Vec3*, std::size_t, const double[3], double, std::uint32_t,
                            std::uint64_t*) {
  assert(false && "no AVX2 kernels in this build");
  return {};
}
#endif

}  // namespace detail

void morton_order(const Vec3* points, std::size_t n, const BoundingBox& box,
                  std::vector<std::uint32_t>& order, std::vector<std::uint64_t>& keys) {
  assert(n < (std::size_t{1} << 32));
  order.resize(n);
  std::iota(order.begin(), order.end(), 0u);
  const MortonGrid grid(box);
  if (n < 3 || !grid.valid()) return;
  keys.resize(2 * n);  // the codes, then the radix sort's second buffer
#if defined(MESHDEV_X86_KERNELS)
  static const bool avx2 = simd_level() != SimdLevel::kBaseline;
#else
  constexpr bool avx2 = false;
#endif
  const Vec3& o = grid.origin();
  const double origin[3] = {o.x, o.y, o.z};
  const detail::MortonRun run =
      avx2 ? detail::morton_codes_avx2(points, n, origin, grid.cells_per_unit(),
                                       MortonGrid::max_cell(), keys.data())
           : detail::morton_codes(grid, points, n, keys.data());
  const std::size_t descents = run.descents;
  const std::uint64_t least = run.least, most = run.most;
  if (descents == 0) return;
  // Every code shares the bits above the highest one in which the least and the most differ;
  // sort by the kMortonSortBits bits from that one down, with the point's index in the low word.
  constexpr int kPassBits = 8;
  static_assert(kMortonSortBits % kPassBits == 0, "whole passes");
  constexpr std::uint64_t kMask = (std::uint64_t{1} << kMortonSortBits) - 1;
  const int top = 63 - __builtin_clzll(least ^ most);  // least != most: there is a descent
  const int low = std::max(0, top - (kMortonSortBits - 1));
  for (std::size_t i = 0; i < n; ++i) keys[i] = (keys[i] >> low & kMask) << 32 | i;
  // LSD radix sort on those bits, 8 per pass (stable: equal keys keep their order).
  std::uint64_t* from = keys.data();
  std::uint64_t* to = keys.data() + n;
  constexpr std::size_t kBins = std::size_t{1} << kPassBits;
  for (int shift = 32; shift < 32 + kMortonSortBits; shift += kPassBits) {
    std::size_t start[kBins + 1] = {};
    for (std::size_t i = 0; i < n; ++i) ++start[(from[i] >> shift & (kBins - 1)) + 1];
    for (std::size_t b = 0; b < kBins; ++b) start[b + 1] += start[b];
    for (std::size_t i = 0; i < n; ++i) to[start[from[i] >> shift & (kBins - 1)]++] = from[i];
    std::swap(from, to);
  }
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(from[i]);
}

}  // namespace meshdev
