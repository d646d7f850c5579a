#include "metric/morton_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

namespace meshdev {
namespace {

// The brute-force twin: the code bit by bit, then a stable sort by it.
std::vector<std::uint32_t> reference_order(const std::vector<Vec3>& p) {
  Vec3 lo = p[0], hi = p[0];
  for (const Vec3& x : p) {
    lo = {std::min(lo.x, x.x), std::min(lo.y, x.y), std::min(lo.z, x.z)};
    hi = {std::max(hi.x, x.x), std::max(hi.y, x.y), std::max(hi.z, x.z)};
  }
  const double scale = 1023.0 / std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  std::vector<std::uint64_t> code(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double c[3] = {p[i].x - lo.x, p[i].y - lo.y, p[i].z - lo.z};
    for (int axis = 0; axis < 3; ++axis) {
      const auto cell = static_cast<std::uint64_t>(std::min(c[axis] * scale, 1023.0));
      for (int bit = 0; bit < 10; ++bit) code[i] |= (cell >> bit & 1u) << (3 * bit + axis);
    }
  }
  std::vector<std::uint32_t> order(p.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return code[a] < code[b]; });
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
    morton_order(p.data(), n, order, keys);
    EXPECT_EQ(order, reference_order(p)) << n;
  }
}

TEST(MortonOrder, VisitsAGridCellByCell) {
  // The 4 x 4 grid in row order: the Z curve takes 2 x 2 blocks in turn.
  std::vector<Vec3> p;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) p.push_back({double(x), double(y), 0.0});
  std::vector<std::uint32_t> order;
  std::vector<std::uint64_t> keys;
  morton_order(p.data(), p.size(), order, keys);
  const std::vector<std::uint32_t> z = {0, 1, 4, 5, 2, 3, 6, 7, 8, 9, 12, 13, 10, 11, 14, 15};
  EXPECT_EQ(order, z);
  // Points already in that order are left as they are.
  std::vector<Vec3> sorted;
  for (std::uint32_t i : z) sorted.push_back(p[i]);
  morton_order(sorted.data(), sorted.size(), order, keys);
  for (std::uint32_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
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
    morton_order(p.data(), p.size(), order, keys);
    ASSERT_EQ(order.size(), p.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
  }
}

}  // namespace
}  // namespace meshdev
