#pragma once
// The order of a run of points along a Morton (Z-order) curve.
//
// Consecutive points of that order are near each other, which is what the nearest-point indices
// need from a batch (TriangleBvh::find_batch answers near-by queries in packets and starts each
// query from the previous one's face): samples generated face by face are near each other only
// up to their face's size, and Monte Carlo samples inside a face come in random order.
//
// Codes: 21 bits per axis on a cubic grid over a box the caller gives (for compute_deviations,
// the reference mesh's box, which holds all its samples, so a run cut from a set already sorted
// along that curve is recognised as sorted), interleaved x-y-z (x in the lowest bit). A run is
// sorted by the kMortonSortBits highest bits in which its codes differ (finer bits keep the input
// order).
// Deterministic. Ref: Morton, "A computer oriented geodetic data base..." (IBM, 1966).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "metric/mesh.h"

namespace meshdev {

namespace detail {
// The 7 bits of x spread to every third bit (bit k -> bit 3k), for x in [0, 128).
struct MortonSpread {
  std::uint64_t bits[128] = {};
  constexpr MortonSpread() {
    for (std::uint64_t x = 0; x < 128; ++x)
      for (int k = 0; k < 7; ++k) bits[x] |= (x >> k & 1u) << (3 * k);
  }
};
inline constexpr MortonSpread kMortonSpread{};
}  // namespace detail

// The bits a run is sorted by (morton_order): 24, three radix passes of 8. A run of 1,024 points
// then has about 16,000 cells per point; 30 bits (four passes) cost more for the same queries,
// 22 bits in two passes of 11 more still (the 2,048-bin prefix sums; docs/performance-log.md).
inline constexpr int kMortonSortBits = 24;

// The cubic grid over a box that the codes are taken on: 2^21 cells per axis.
class MortonGrid {
 public:
  // Buckets: the grid's cells at level kBucketLevels (2^6 per axis; the codes' top 18 bits), in
  // Morton order.
  static constexpr int kBucketLevels = 6;
  static constexpr std::uint32_t kBuckets = 1u << (3 * kBucketLevels);

  explicit MortonGrid(const BoundingBox& box);
  // False for an empty or non-finite box (or a single point): every point is then in cell 0.
  bool valid() const { return scale_ > 0.0; }
  // The grid's corner, cells per unit length and largest cell index (code's arithmetic).
  const Vec3& origin() const { return min_; }
  double cells_per_unit() const { return scale_; }
  static constexpr std::uint32_t max_cell() { return kMaxCell; }
  // The Morton code of p's cell, x-y-z interleaved (x in the lowest bit); points outside the box
  // (or NaN) are clamped to it. O(1).
  std::uint64_t code(const Vec3& p) const {
    return spread21(cell(p.x, min_.x)) | spread21(cell(p.y, min_.y)) << 1 |
           spread21(cell(p.z, min_.z)) << 2;
  }
  // p's bucket, in [0, kBuckets): the top 3 x kBucketLevels bits of code(p)'s 63. O(1).
  std::uint32_t bucket(const Vec3& p) const {
    static_assert(kBucketLevels <= 7, "one lookup per axis");
    constexpr int shift = 21 - kBucketLevels;
    const auto& spread = detail::kMortonSpread.bits;
    return static_cast<std::uint32_t>(spread[cell(p.x, min_.x) >> shift] |
                                      spread[cell(p.y, min_.y) >> shift] << 1 |
                                      spread[cell(p.z, min_.z) >> shift] << 2);
  }

 private:
  static constexpr std::uint32_t kMaxCell = (1u << 21) - 1;
  // The cell of coordinate x along an axis starting at x0: in [0, kMaxCell]; NaN: 0.
  std::uint32_t cell(double x, double x0) const {
    const double t = (x - x0) * scale_;
    return t >= 0.0 ? (t < kMaxCell ? static_cast<std::uint32_t>(t) : kMaxCell) : 0u;
  }
  // The 21 bits of x spread to every third bit.
  static std::uint64_t spread21(std::uint32_t x) {
    const auto& spread = detail::kMortonSpread.bits;
    return spread[x & 127u] | spread[x >> 7 & 127u] << 21 | spread[x >> 14 & 127u] << 42;
  }

  Vec3 min_;
  double scale_ = 0.0;
};

// Writes to `order` the permutation that sorts `bucket[0..n)` (values < MortonGrid::kBuckets)
// stably: a counting sort. Returns false, with `order` empty, if they are already sorted (the
// identity). For a set too large for morton_order's runs to be near each other: sorted by
// bucket first, its runs cover a few coarse cells each, and morton_order orders each run.
// O(n + kBuckets); n < 2^32.
bool stable_bucket_order(const std::uint32_t* bucket, std::size_t n,
                         std::vector<std::uint32_t>& order);

namespace detail {
// What morton_order needs to know of a run's codes.
struct MortonRun {
  std::size_t descents = 0;                 // codes below the one before
  std::uint64_t least = ~std::uint64_t{0};  // the least and the greatest code
  std::uint64_t most = 0;
};
// codes[i] = grid.code(points[i]) for i < n, and the run's MortonRun: morton_order's first pass,
// one point at a time (the twin of the AVX2 version below). O(n).
MortonRun morton_codes(const MortonGrid& grid, const Vec3* points, std::size_t n,
                       std::uint64_t* codes);
// The same, bit for bit, four points at a time in AVX2 lanes (metric/morton_codes_avx2.cpp), for
// origin = grid.origin(), scale = grid.cells_per_unit(), max_cell = MortonGrid::max_cell(): the
// cells from the same double operations, spread by shifts and masks instead of a table. On
// samples already in order (a run cut from a sorted set), chunk-interleaved, 2 threads, three
// runs: torus100k -> 10k +1.3 / +2.8 / +1.4 %, armadillo +1.5 / +1.8 / +1.8 %, torus100k -> 1m
// +1.6 / +1.9 / +0.3 %, torus1m -> 100k +1.6 / +0.9 / +1.3 % (docs/performance-log.md §3).
// Precondition: the CPU runs AVX2 (simd_level() != kBaseline, metric/plane_bounds.h); builds
// without the x86 kernels only assert. O(n).
MortonRun morton_codes_avx2(const Vec3* points, std::size_t n, const double origin[3], double scale,
                            std::uint32_t max_cell, std::uint64_t* codes);
}  // namespace detail

// Writes to `order` the permutation of [0, n) that visits points[0..n) in Morton order of their
// cells in `box`; `keys` is scratch. The identity if the codes are already non-decreasing, or if
// the box is empty or not finite. Points outside the box (or NaN) are clamped to it. The codes
// are computed four at a time where simd_level() allows (the same codes); like it, throws
// InvalidInput for a bad MESHDEV_SIMD. O(n): a check, then a radix sort of 3 passes; n < 2^32.
void morton_order(const Vec3* points, std::size_t n, const BoundingBox& box,
                  std::vector<std::uint32_t>& order, std::vector<std::uint64_t>& keys);

}  // namespace meshdev
