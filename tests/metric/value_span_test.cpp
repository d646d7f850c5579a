#include "metric/value_span.h"

#include <gtest/gtest.h>

#include <vector>

#include "metric/raw_storage_allocator.h"

namespace meshdev {
namespace {

TEST(ConstSpan, ViewsAnyContiguousVectorWithoutCopying) {
  const std::vector<double> plain{1, 2, 3};
  const std::vector<double, RawStorageAllocator<double>> raw{4, 5};
  const ConstSpan<double> a = plain, b = raw, empty;
  EXPECT_EQ(a.data(), plain.data());
  EXPECT_EQ(a.size(), 3u);
  EXPECT_EQ(b.data(), raw.data());
  EXPECT_EQ(b[1], 5.0);
  EXPECT_TRUE(empty.empty());
  double sum = 0;
  for (double x : a) sum += x;
  EXPECT_EQ(sum, 6.0);
}

}  // namespace
}  // namespace meshdev
