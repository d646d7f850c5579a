#include "metric/key_ranks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "metric/plane_bounds.h"

namespace meshdev {
namespace {

// The definition by sorting: rank[i] = the position of key[i] in the keys sorted.
std::vector<std::uint32_t> sorted_ranks(const std::vector<std::uint64_t>& key) {
  std::vector<std::uint32_t> order(key.size()), rank(key.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
  for (std::uint32_t r = 0; r < order.size(); ++r) rank[order[r]] = r;
  return rank;
}

// Distinct keys of every count up to kMaxRankKeys, from narrow and full 64-bit ranges (top bits
// set: the AVX2 version's signed comparison must give the unsigned order) and the extremes 0 and
// 2^64 - 1: both versions give the ranks of the sorted order.
TEST(KeyRanks, BothVersionsGiveTheSortedOrdersRanks) {
  const bool avx = simd_level() != SimdLevel::kBaseline;
  std::mt19937_64 rng(47);
  for (int round = 0; round < 2000; ++round) {
    const auto count = static_cast<std::uint32_t>(round % (detail::kMaxRankKeys + 1));
    std::vector<std::uint64_t> key;
    while (key.size() < count) {
      std::uint64_t k = rng();
      if (round % 4 == 1) k %= 100;                     // small keys, dense
      if (round % 4 == 2) k |= std::uint64_t{1} << 63;  // all with the top bit
      if (round % 4 == 3 && key.size() < 2) k = key.empty() ? 0 : ~std::uint64_t{0};
      if (std::find(key.begin(), key.end(), k) == key.end()) key.push_back(k);
    }
    const std::vector<std::uint32_t> expected = sorted_ranks(key);
    std::vector<std::uint32_t> rank(count + 1, 12345);
    detail::key_ranks(key.data(), count, rank.data());
    EXPECT_EQ(std::vector<std::uint32_t>(rank.begin(), rank.begin() + count), expected);
    EXPECT_EQ(rank[count], 12345u);  // nothing written past count
    if (!avx) continue;
    std::vector<std::uint32_t> fast(count + 1, 12345);
    detail::key_ranks_avx2(key.data(), count, fast.data());
    EXPECT_EQ(fast, rank);
  }
}

}  // namespace
}  // namespace meshdev
