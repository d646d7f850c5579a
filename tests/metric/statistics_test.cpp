#include "metric/statistics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace meshdev {
namespace {

TEST(Statistics, UnweightedMomentsAndExtremes) {
  Statistics s = compute_statistics({1, 2, 3, 4}, {});
  EXPECT_EQ(s.count, 4u);
  EXPECT_EQ(s.min, 1.0);
  EXPECT_EQ(s.max, 4.0);
  EXPECT_EQ(s.argmax, 3u);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.variance, 1.25);  // population variance
  EXPECT_DOUBLE_EQ(s.rms, std::sqrt(7.5));
  EXPECT_EQ(s.p50, 2.0);
  EXPECT_EQ(s.p99, 4.0);
  EXPECT_FALSE(s.area_weighted);
}

TEST(Statistics, WeightsShiftMeanAndQuantilesButNotExtremes) {
  Statistics s = compute_statistics({0, 10, 100}, {1, 3, 0});
  EXPECT_DOUBLE_EQ(s.mean, 7.5);
  EXPECT_EQ(s.max, 100.0);  // a zero-weight sample still counts for the maximum
  EXPECT_EQ(s.p50, 10.0);
  EXPECT_EQ(s.p99, 10.0);
  EXPECT_TRUE(s.area_weighted);
  EXPECT_DOUBLE_EQ(s.weight_sum, 4.0);
}

TEST(Statistics, AllZeroWeightsFallBackToEqualWeights) {
  Statistics s = compute_statistics({1, 3}, {0, 0});
  EXPECT_DOUBLE_EQ(s.mean, 2.0);
}

TEST(Statistics, HistogramCountsEverySampleOnce) {
  std::vector<double> v;
  for (int i = 0; i < 1000; ++i) v.push_back(i / 999.0);
  Statistics s = compute_statistics(v, {}, 10);
  std::size_t total = 0;
  double fraction = 0;
  for (std::size_t b = 0; b < s.histogram.counts.size(); ++b) {
    total += s.histogram.counts[b];
    fraction += s.histogram.weight_fraction[b];
  }
  EXPECT_EQ(total, 1000u);
  EXPECT_NEAR(fraction, 1.0, 1e-12);
  EXPECT_EQ(s.histogram.edges.front(), 0.0);
  EXPECT_EQ(s.histogram.edges.back(), 1.0);
}

TEST(Statistics, ZeroValuesGiveExactZeros) {
  Statistics s = compute_statistics(std::vector<double>(100, 0.0), {});
  EXPECT_EQ(s.max, 0.0);
  EXPECT_EQ(s.mean, 0.0);
  EXPECT_EQ(s.rms, 0.0);
  EXPECT_EQ(s.variance, 0.0);
}

}  // namespace
}  // namespace meshdev
