#include "metric/raw_storage_allocator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace meshdev {
namespace {

TEST(RawStorageAllocator, ConstructsWhatItIsGivenAndCopiesAsAVector) {
  std::vector<double, RawStorageAllocator<double>> v;
  v.push_back(1.5);
  v.resize(3);  // elements 1 and 2 are raw: written before any read
  v[1] = 2.5;
  v[2] = -1.0;
  v.insert(v.begin(), 0.25);
  const std::vector<double, RawStorageAllocator<double>> copy = v;
  EXPECT_EQ(copy, (std::vector<double, RawStorageAllocator<double>>{0.25, 1.5, 2.5, -1.0}));
  std::vector<int, RawStorageAllocator<int>> counted(4, 7);  // the fill constructor constructs
  for (int x : counted) EXPECT_EQ(x, 7);
}

// In the sanitizer builds (scripts/sanitize.sh) a fresh block is all-ones bytes, so an element
// read before it is written is NaN (or 0xffffffff) and the oracle tests catch it. Skipped in the
// other builds, where the storage is left as the allocator returned it.
TEST(RawStorageAllocator, PoisonsFreshStorageInTheSanitizerBuilds) {
#ifndef MESHDEV_POISON_RAW_STORAGE
  GTEST_SKIP() << "not a sanitizer build: raw storage is not poisoned";
#else
  std::vector<double, RawStorageAllocator<double>> d;
  d.resize(1000);
  for (double x : d) ASSERT_TRUE(std::isnan(x));
  std::vector<std::uint32_t, RawStorageAllocator<std::uint32_t>> u;
  u.resize(1000);
  for (std::uint32_t x : u) ASSERT_EQ(x, 0xffffffffu);
  d.resize(5000);  // a reallocation: the moved elements are copies, the new ones poisoned
  for (std::size_t i = 1000; i < d.size(); ++i) ASSERT_TRUE(std::isnan(d[i]));
#endif
}

struct Pair32 {  // a trivial 32-byte element, as the BVH build's binary nodes
  float lo[3], hi[3];
  std::uint32_t index, count;
};
struct Block176 {  // a trivial 176-byte element, as its leaf blocks
  float corner[3][3][4];
  float margin[4];
  std::uint32_t face[4];
};

TEST(RawArray, HoldsItsCountAndMovesItsStorage) {
  RawArray<double> a(1000);
  EXPECT_EQ(a.size(), 1000u);
  ASSERT_NE(a.data(), nullptr);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = 0.5 * static_cast<double>(i);
  const double* storage = a.data();
  RawArray<double> b(std::move(a));
  EXPECT_EQ(b.data(), storage);  // the same storage, not a copy
  EXPECT_EQ(b.size(), 1000u);
  EXPECT_EQ(a.size(), 0u);  // NOLINT(bugprone-use-after-move): moved-from arrays are empty
  EXPECT_EQ(a.data(), nullptr);
  EXPECT_EQ(b[999], 499.5);
  RawArray<double> c;
  c = std::move(b);
  EXPECT_EQ(c.data(), storage);
  EXPECT_EQ(b.data(), nullptr);  // NOLINT(bugprone-use-after-move)
  RawArray<double> empty(0);
  EXPECT_EQ(empty.size(), 0u);
}

TEST(RawArray, TakesOverTheStorageOfAnotherTypeCutToItsCount) {
  RawArray<Pair32> tree(2000);  // 64,000 bytes
  for (std::size_t i = 0; i < tree.size(); ++i) tree[i].index = static_cast<std::uint32_t>(i);
  RawArray<Block176> blocks(std::move(tree), 300);  // 52,800 bytes of them
  EXPECT_EQ(tree.size(), 0u);                       // NOLINT(bugprone-use-after-move)
  EXPECT_EQ(tree.data(), nullptr);
  EXPECT_EQ(blocks.size(), 300u);
  ASSERT_NE(blocks.data(), nullptr);
  for (std::size_t i = 0; i < blocks.size(); ++i) blocks[i].face[3] = static_cast<std::uint32_t>(i);
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < blocks.size(); ++i) sum += blocks[i].face[3];
  EXPECT_EQ(sum, 299u * 300u / 2);
}

// As RawStorageAllocator's: a fresh array, and one that took over another's storage, hold
// all-ones bytes in the sanitizer builds.
TEST(RawArray, PoisonsItsElementsInTheSanitizerBuilds) {
#ifndef MESHDEV_POISON_RAW_STORAGE
  GTEST_SKIP() << "not a sanitizer build: raw storage is not poisoned";
#else
  RawArray<double> d(1000);
  for (std::size_t i = 0; i < d.size(); ++i) ASSERT_TRUE(std::isnan(d[i]));
  RawArray<Pair32> tree(100);
  for (std::size_t i = 0; i < tree.size(); ++i) tree[i] = Pair32{{0, 0, 0}, {0, 0, 0}, 0, 0};
  RawArray<Block176> blocks(std::move(tree), 10);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    ASSERT_TRUE(std::isnan(blocks[i].margin[0]));
    ASSERT_EQ(blocks[i].face[0], 0xffffffffu);
  }
#endif
}

}  // namespace
}  // namespace meshdev
