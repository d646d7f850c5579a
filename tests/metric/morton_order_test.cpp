#include "metric/morton_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <string>

#include "metric/plane_bounds.h"

namespace meshdev {
namespace {

BoundingBox box_of(const std::vector<Vec3>& p) {
  BoundingBox box;
  for (const Vec3& x : p) box.extend(x);
  return box;
}

// The brute-force twin: each code bit by bit, then a stable sort by the kMortonSortBits highest
// bits in which the codes differ.
std::vector<std::uint32_t> reference_order(const std::vector<Vec3>& p, const BoundingBox& box) {
  const Vec3 e = box.max - box.min;
  const double scale = 2097151.0 / std::max({e.x, e.y, e.z});
  std::vector<std::uint64_t> code(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double c[3] = {p[i].x - box.min.x, p[i].y - box.min.y, p[i].z - box.min.z};
    for (int axis = 0; axis < 3; ++axis) {
      const auto cell = static_cast<std::uint64_t>(std::min(c[axis] * scale, 2097151.0));
      for (int bit = 0; bit < 21; ++bit) code[i] |= (cell >> bit & 1u) << (3 * bit + axis);
    }
  }
  const auto [least, most] = std::minmax_element(code.begin(), code.end());
  int top = 63;
  while (top > 0 && ((*least ^ *most) >> top & 1u) == 0) --top;
  const int low = std::max(0, top - (kMortonSortBits - 1));
  const std::uint64_t mask = (std::uint64_t{1} << kMortonSortBits) - 1;
  std::vector<std::uint32_t> order(p.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return (code[a] >> low & mask) < (code[b] >> low & mask);
  });
  return order;
}

TEST(MortonOrder, EqualsTheBitByBitReferenceOnRandomClouds) {
  std::mt19937_64 rng(7);
  std::vector<std::uint32_t> order;
  std::vector<std::uint64_t> keys;
  for (std::size_t n : {3u, 17u, 1024u, 5000u}) {
    std::uniform_real_distribution<double> u(-3.0, 5.0);
    std::vector<Vec3> p(n);
    for (Vec3& x : p) x = {u(rng), u(rng), 0.25 * u(rng)};
    p[n / 2] = p[0];  // equal codes keep their input order
    const BoundingBox box = box_of(p);
    morton_order(p.data(), n, box, order, keys);
    EXPECT_EQ(order, reference_order(p, box)) << n;
    // A run inside a larger box: codes share their top bits, the sort uses the next 30.
    BoundingBox wide = box;
    wide.extend({1e3, 1e3, 1e3});
    morton_order(p.data(), n, wide, order, keys);
    EXPECT_EQ(order, reference_order(p, wide)) << n;
  }
}

// The AVX2 codes against the one-point twin (MortonGrid::code through its table), bit for bit,
// with the run's descents and extremes: points inside and outside the box, on its faces, NaN,
// infinite and -0 coordinates, every length from 0 to 9 (the tails of one to three) and longer
// runs, sorted and not.
TEST(MortonOrder, Avx2CodesEqualTheOnePointCodes) {
  if (simd_level() == SimdLevel::kBaseline)
    GTEST_SKIP() << "the CPU (or MESHDEV_SIMD=baseline) has no AVX2: the kernel is never entered";
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-0.5, 1.5);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double special[] = {nan, inf, -inf, -0.0, 0.0, 1.0, 1e300, -1e300, 0.999999999};
  BoundingBox box;
  box.extend({0, 0, 0});
  box.extend({1, 2, 0.5});
  const MortonGrid grid(box);
  const double origin[3] = {grid.origin().x, grid.origin().y, grid.origin().z};
  std::vector<std::uint64_t> simd, twin;
  for (std::size_t n : {0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u, 1000u, 4099u}) {
    for (const bool sorted : {false, true}) {
      std::vector<Vec3> p(n);
      for (std::size_t i = 0; i < n; ++i) {
        for (int k = 0; k < 3; ++k) p[i][k] = u(rng);
        if (i % 7 == 3) p[i][static_cast<int>(i % 3)] = special[(i / 7) % std::size(special)];
      }
      if (sorted)
        std::sort(p.begin(), p.end(),
                  [&](const Vec3& a, const Vec3& b) { return grid.code(a) < grid.code(b); });
      simd.assign(n, 0);
      twin.assign(n, 1);
      const detail::MortonRun a = detail::morton_codes_avx2(
          p.data(), n, origin, grid.cells_per_unit(), MortonGrid::max_cell(), simd.data());
      const detail::MortonRun b = detail::morton_codes(grid, p.data(), n, twin.data());
      SCOPED_TRACE("n " + std::to_string(n) + (sorted ? ", sorted" : ""));
      EXPECT_EQ(simd, twin);
      EXPECT_EQ(a.descents, b.descents);
      EXPECT_EQ(a.least, b.least);
      EXPECT_EQ(a.most, b.most);
      if (sorted) {
        EXPECT_EQ(a.descents, 0u);
      } else if (n >= 9) {
        EXPECT_GT(a.descents, 0u);
      }
    }
  }
}

TEST(MortonOrder, VisitsAGridCellByCell) {
  // The 4 x 4 grid in row order: the Z curve takes 2 x 2 blocks in turn.
  std::vector<Vec3> p;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) p.push_back({double(x), double(y), 0.0});
  std::vector<std::uint32_t> order;
  std::vector<std::uint64_t> keys;
  morton_order(p.data(), p.size(), box_of(p), order, keys);
  const std::vector<std::uint32_t> z = {0, 1, 4, 5, 2, 3, 6, 7, 8, 9, 12, 13, 10, 11, 14, 15};
  EXPECT_EQ(order, z);
}

// What compute_deviations relies on to leave sorted samples alone: a run cut from a set sorted
// along the curve of the same box (by the whole codes, as peer_compare --order morton sorts) is
// already in order.
TEST(MortonOrder, RunsOfASortedSetAreLeftAsTheyAre) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> p(20000);
  for (Vec3& x : p) x = {u(rng), 2 * u(rng), u(rng)};
  const BoundingBox box = box_of(p);
  const MortonGrid grid(box);
  std::vector<Vec3> sorted = p;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [&](const Vec3& a, const Vec3& b) { return grid.code(a) < grid.code(b); });
  std::vector<std::uint32_t> order;
  std::vector<std::uint64_t> keys;
  for (std::size_t begin : {0u, 1024u, 7000u, 18976u}) {
    morton_order(sorted.data() + begin, 1024, box, order, keys);
    for (std::uint32_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], i) << begin;
  }
}

TEST(MortonOrder, BucketsAreTheCodesTopBits) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 3.0);  // partly outside the box: clamped
  BoundingBox box;
  box.extend({0, 0, 0});
  box.extend({2, 1, 0.5});
  const MortonGrid grid(box);
  ASSERT_TRUE(grid.valid());
  for (int i = 0; i < 10000; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    ASSERT_EQ(grid.bucket(p), grid.code(p) >> (63 - 3 * MortonGrid::kBucketLevels)) << i;
  }
  EXPECT_EQ(grid.bucket({2, 1, 0.5}),
            grid.code({2, 1, 0.5}) >> (63 - 3 * MortonGrid::kBucketLevels));
  EXPECT_EQ(grid.bucket({std::nan(""), 0, 0}),
            grid.code({std::nan(""), 0, 0}) >> (63 - 3 * MortonGrid::kBucketLevels));
  EXPECT_LT(grid.code({2, 1, 0.5}), std::uint64_t{1} << 63);
}

// The twin of the counting sort: std::stable_sort of the indices by bucket.
TEST(MortonOrder, StableBucketOrderIsAStableSort) {
  std::mt19937_64 rng(11);
  std::vector<std::uint32_t> order;
  for (std::size_t n : {1u, 2u, 1000u, 70000u}) {
    std::uniform_int_distribution<std::uint32_t> b(0, n < 100 ? 3 : MortonGrid::kBuckets - 1);
    std::vector<std::uint32_t> bucket(n);
    for (auto& x : bucket) x = static_cast<std::uint32_t>(b(rng));
    std::vector<std::uint32_t> want(n);
    std::iota(want.begin(), want.end(), 0u);
    std::stable_sort(want.begin(), want.end(),
                     [&](std::uint32_t x, std::uint32_t y) { return bucket[x] < bucket[y]; });
    const bool moved = stable_bucket_order(bucket.data(), n, order);
    if (std::is_sorted(bucket.begin(), bucket.end())) {
      EXPECT_FALSE(moved) << n;
      EXPECT_TRUE(order.empty()) << n;
    } else {
      EXPECT_TRUE(moved) << n;
      EXPECT_EQ(order, want) << n;
    }
  }
  std::vector<std::uint32_t> sorted = {0, 0, 5, 7, 7, MortonGrid::kBuckets - 1};
  EXPECT_FALSE(stable_bucket_order(sorted.data(), sorted.size(), order));
  EXPECT_TRUE(order.empty());
}

TEST(MortonOrder, IdentityForOnePointOrANonFiniteBox) {
  std::vector<std::uint32_t> order;
  std::vector<std::uint64_t> keys;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const std::vector<Vec3>& p :
       {std::vector<Vec3>{{1, 2, 3}, {1, 2, 3}, {1, 2, 3}},
        std::vector<Vec3>{{nan, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
        std::vector<Vec3>{{0, 0, 0}, {inf, 0, 0}, {0, 1, 0}}}) {
    BoundingBox box;
    box.min = p[0];
    box.max = p[0];
    for (const Vec3& x : p) {
      box.min = {std::min(box.min.x, x.x), std::min(box.min.y, x.y), std::min(box.min.z, x.z)};
      box.max = {std::max(box.max.x, x.x), std::max(box.max.y, x.y), std::max(box.max.z, x.z)};
    }
    morton_order(p.data(), p.size(), box, order, keys);
    ASSERT_EQ(order.size(), p.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
  }
}

}  // namespace
}  // namespace meshdev
