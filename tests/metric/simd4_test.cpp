#include "metric/simd4.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <vector>

namespace meshdev {
namespace {

bool same_bits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(Simd4, ScalarMinAndMaxAreStdMinAndMaxBitForBit) {
  // The packet box's growth (triangle_bvh.cpp, find_batch) takes min1(q, lo) for std::min(lo, q)
  // and max1(q, hi) for std::max(hi, q): the same value in every case, signed zeros, infinities
  // and NaN included (where std::min(x, NaN) and std::max(x, NaN) give x).
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> values = {0.0f,  -0.0f, 1.0f, -1.0f, 1e-30f,
                                     -3.5f, 2.25f, inf,  -inf,  nan};
  for (float box : values)
    for (float q : values) {
      SCOPED_TRACE(testing::Message() << "box " << box << ", q " << q);
      EXPECT_TRUE(same_bits(simd::min1(q, box), std::min(box, q)));
      EXPECT_TRUE(same_bits(simd::max1(q, box), std::max(box, q)));
    }
}

}  // namespace
}  // namespace meshdev
