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

}  // namespace
}  // namespace meshdev
