#include "metric/statistics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace meshdev {
namespace {

TEST(Statistics, UnweightedMomentsAndExtremes) {
  Statistics s = compute_statistics(std::vector<double>{1, 2, 3, 4}, {});
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
  Statistics s = compute_statistics(std::vector<double>{0, 10, 100}, {1, 3, 0});
  EXPECT_DOUBLE_EQ(s.mean, 7.5);
  EXPECT_EQ(s.max, 100.0);  // a zero-weight sample still counts for the maximum
  EXPECT_EQ(s.p50, 10.0);
  EXPECT_EQ(s.p99, 10.0);
  EXPECT_TRUE(s.area_weighted);
  EXPECT_DOUBLE_EQ(s.weight_sum, 4.0);
}

// Equal weights take a selection path (nth_element); it must give the order statistics the
// weighted definition gives: the smallest value whose cumulative weight reaches q of the total.
TEST(Statistics, EqualWeightQuantilesAreTheOrderStatisticsOfTheDefinition) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t n : {1u, 2u, 3u, 7u, 100u, 101u, 1000u, 4999u}) {
    std::vector<double> values(n);
    for (double& v : values) v = std::floor(u(rng) * 50.0) / 7.0;  // many equal values
    const Statistics s = compute_statistics(values, std::vector<double>(n, 0.25));
    EXPECT_FALSE(s.area_weighted);
    std::vector<double> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    const double qs[4] = {0.50, 0.90, 0.95, 0.99};
    const double got[4] = {s.p50, s.p90, s.p95, s.p99};
    for (int q = 0; q < 4; ++q) {
      std::size_t k = 0;  // smallest k with (k + 1) / n >= q, counted exactly
      while (static_cast<double>(k + 1) < qs[q] * static_cast<double>(n)) ++k;
      EXPECT_EQ(got[q], sorted[k]) << "n " << n << " q " << qs[q];
    }
  }
}

// The sorted twin of the quantiles: all (value, weight) pairs sorted (weights all 1 when `weights`
// is empty), weights summed in that order; p50, p90, p95, p99 are the first values whose
// cumulative weight reaches q of the total.
std::array<double, 4> sorted_twin_quantiles(const std::vector<double>& values,
                                            const std::vector<double>& weights) {
  const std::size_t n = values.size();
  std::vector<std::pair<double, double>> sorted(n);
  for (std::size_t i = 0; i < n; ++i) sorted[i] = {values[i], weights.empty() ? 1.0 : weights[i]};
  std::sort(sorted.begin(), sorted.end());
  double total = 0;
  for (const auto& p : sorted) total += p.second;
  const double qs[4] = {0.50, 0.90, 0.95, 0.99};
  std::array<double, 4> want;
  for (int q = 0; q < 4; ++q) {
    double cum = 0;
    want[q] = sorted.back().first;
    for (const auto& p : sorted)
      if ((cum += p.second) >= qs[q] * total) {
        want[q] = p.first;
        break;
      }
  }
  return want;
}

// compute_statistics' quantiles of `values`, with equal weights and then with `weights`, must be
// the sorted twin's exactly, on teams of 1, 2 and 3 threads (sets of more than one block gather
// the quantiles' bins on every thread).
void expect_quantiles_are_the_sorted_twins(const std::vector<double>& values,
                                           const std::vector<double>& weights,
                                           const std::string& what) {
  for (bool weighted : {false, true}) {
    const std::vector<double> w = weighted ? weights : std::vector<double>{};
    const std::array<double, 4> want = sorted_twin_quantiles(values, w);
    for (int threads : {1, 2, 3}) {
      const Statistics s = compute_statistics(values, w, 32, threads);
      const double got[4] = {s.p50, s.p90, s.p95, s.p99};
      for (int q = 0; q < 4; ++q)
        EXPECT_EQ(got[q], want[q])
            << what << " weighted " << weighted << " q " << q << " threads " << threads;
    }
  }
}

// Quantiles are found bin by bin (a histogram pass, then selection or a sort inside the
// quantile's bin). The twin: all (value, weight) pairs sorted, weights summed in that order.
// Samples of up to 200k values (up to 12,500 bins), skewed, with many zeros and equal values,
// zero weights (vertex samples) and an outlier that squeezes most values into the first bins.
TEST(Statistics, BinnedQuantilesEqualTheSortedTwin) {
  std::mt19937_64 rng(11);
  std::exponential_distribution<double> e(3.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t n : {50u, 1000u, 20000u, 200000u}) {
    for (int shape = 0; shape < 3; ++shape) {
      std::vector<double> values(n), weights(n);
      for (std::size_t i = 0; i < n; ++i) {
        const double r = u(rng);
        values[i] = r < 0.2 ? 0.0 : (shape == 1 ? std::floor(e(rng) * 20) / 20 : e(rng));
        weights[i] = r > 0.9 ? 0.0 : u(rng);
      }
      if (shape == 2) values[n / 3] = 1e9;  // an outlier
      expect_quantiles_are_the_sorted_twins(
          values, weights, "n " + std::to_string(n) + " shape " + std::to_string(shape));
    }
  }
}

// Samples where many values equal the minimum (the exact zeros of coplanar parts, here a
// minimum of 0.25): quantiles below that share are the minimum without a selection, the others
// are ranked past it. Counts of minimum values on both sides of each quantile's rank.
TEST(Statistics, QuantilesOfSamplesMostlyAtTheirMinimum) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t n : {1000u, 100000u}) {
    for (std::size_t at_min :
         {n / 2 - 1, n / 2, n / 2 + 1, n * 9 / 10, n * 99 / 100 - 1, n * 99 / 100, n - 1, n}) {
      std::vector<double> values(n), weights(n);
      for (std::size_t i = 0; i < n; ++i) {
        values[i] = 0.25 + u(rng) * u(rng);  // above the minimum, denser near it
        weights[i] = u(rng);
      }
      std::shuffle(values.begin(), values.end(), rng);
      std::vector<std::size_t> order(n);
      std::iota(order.begin(), order.end(), 0);
      std::shuffle(order.begin(), order.end(), rng);
      for (std::size_t i = 0; i < at_min; ++i) values[order[i]] = 0.25;
      expect_quantiles_are_the_sorted_twins(
          values, weights, "n " + std::to_string(n) + " at_min " + std::to_string(at_min));
    }
  }
}

// The fused passes against a plain twin: one quantity per loop, in sample order inside each
// block of kStatisticsBlock values, each sum compensated the same way and the blocks' sums merged
// in block order (so the moments agree bit for bit), histogram shares summed per bin. Values
// repeat their extremes (the first index must win); weights absent, equal or spread; sets of
// one block and of several (the last one short), on teams of 1 and 2 threads.
TEST(Statistics, FusedPassesEqualThePlainTwin) {
  struct Sum {  // Neumaier
    double s = 0, c = 0;
    void add(double x) {
      const double t = s + x;
      c += std::fabs(s) >= std::fabs(x) ? (s - t) + x : (x - t) + s;
      s = t;
    }
    double value() const { return s + c; }
  };
  // Sum of term(i) over [0, n): Neumaier inside each block, the blocks' (s, c) added in order.
  auto blocked_sum = [](std::size_t n, auto term) {
    Sum all;
    for (std::size_t begin = 0; begin < n; begin += kStatisticsBlock) {
      Sum block;
      for (std::size_t i = begin; i < std::min(n, begin + kStatisticsBlock); ++i)
        block.add(term(i));
      all.add(block.s);
      all.add(block.c);
    }
    return all.value();
  };
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t n : {std::size_t{1}, std::size_t{2}, std::size_t{17}, std::size_t{1000},
                        std::size_t{30000}, 2 * kStatisticsBlock + 1001}) {
    std::vector<double> values(n), spread(n);
    for (std::size_t i = 0; i < n; ++i) {
      values[i] = std::floor(u(rng) * 40.0) * 0.37 - 2.0;  // negatives, ties at both ends
      spread[i] = u(rng) < 0.1 ? 0.0 : u(rng);
    }
    for (int mode = 0; mode < 6; ++mode) {
      const int threads = 1 + mode / 3;
      const std::vector<double> weights =
          mode % 3 == 0 ? std::vector<double>{}
                        : (mode % 3 == 1 ? std::vector<double>(n, 0.3) : spread);
      const Statistics s = compute_statistics(values, weights, 7, threads);
      const bool equal =
          weights.empty() || !(blocked_sum(n, [&](std::size_t i) { return weights[i]; }) > 0.0);
      auto w = [&](std::size_t i) { return equal ? 1.0 : weights[i]; };
      const double total = blocked_sum(n, w);
      const double sum = blocked_sum(n, [&](std::size_t i) { return w(i) * values[i]; });
      const double sum_sq =
          blocked_sum(n, [&](std::size_t i) { return w(i) * values[i] * values[i]; });
      const double mean = sum / total;
      const double var = blocked_sum(
          n, [&](std::size_t i) { return w(i) * (values[i] - mean) * (values[i] - mean); });
      const auto lo = std::min_element(values.begin(), values.end());
      const auto hi = std::max_element(values.begin(), values.end());  // the first maximum
      const std::string where = "n " + std::to_string(n) + " mode " + std::to_string(mode);
      EXPECT_EQ(s.min, *lo) << where;
      EXPECT_EQ(s.max, *hi) << where;
      EXPECT_EQ(s.argmin, static_cast<std::size_t>(lo - values.begin())) << where;
      EXPECT_EQ(s.argmax, static_cast<std::size_t>(hi - values.begin())) << where;
      EXPECT_EQ(s.weight_sum, total) << where;
      EXPECT_EQ(s.mean, mean) << where;
      EXPECT_EQ(s.rms, std::sqrt(std::max(0.0, sum_sq / total))) << where;
      EXPECT_EQ(s.variance, var / total) << where;
      EXPECT_EQ(s.area_weighted, mode % 3 == 2 && n > 1 && !equal) << where;
      const double h_lo = std::min(0.0, *lo), h_hi = *hi;
      std::vector<std::size_t> counts(7, 0);
      std::vector<Sum> share(7);
      for (std::size_t i = 0; i < n; ++i) {
        int b = h_hi > h_lo ? static_cast<int>((values[i] - h_lo) / (h_hi - h_lo) * 7) : 0;
        b = std::clamp(b, 0, 6);
        ++counts[b];
        share[b].add(w(i));
      }
      for (int b = 0; b < 7; ++b) {
        EXPECT_EQ(s.histogram.counts[b], counts[b]) << where << " bin " << b;
        EXPECT_NEAR(s.histogram.weight_fraction[b], share[b].value() / total, 1e-15)
            << where << " bin " << b;
      }
    }
  }
}

// Several measures at once (the weights checked once) give each measure's own statistics, field
// by field, for absent, equal, spread and all-zero weights on 1 and 2 threads.
// Every field of two statistics equal, bit for bit.
void expect_same(const Statistics& a, const Statistics& b, const std::string& where) {
  EXPECT_EQ(a.count, b.count) << where;
  EXPECT_EQ(a.weight_sum, b.weight_sum) << where;
  EXPECT_EQ(a.area_weighted, b.area_weighted) << where;
  const double x[] = {a.min, a.max, a.mean, a.variance, a.stddev,
                      a.rms, a.p50, a.p90,  a.p95,      a.p99};
  const double y[] = {b.min, b.max, b.mean, b.variance, b.stddev,
                      b.rms, b.p50, b.p90,  b.p95,      b.p99};
  for (int k = 0; k < 10; ++k) EXPECT_EQ(x[k], y[k]) << where << " field " << k;
  EXPECT_EQ(a.argmin, b.argmin) << where;
  EXPECT_EQ(a.argmax, b.argmax) << where;
  EXPECT_EQ(a.histogram.counts, b.histogram.counts) << where;
  EXPECT_EQ(a.histogram.weight_fraction, b.histogram.weight_fraction) << where;
}

TEST(Statistics, OfEachEqualsEachMeasuresOwn) {
  std::mt19937_64 rng(9);
  std::exponential_distribution<double> e(2.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::size_t n = kStatisticsBlock + 777;
  std::vector<std::vector<double>> measures(3, std::vector<double>(n));
  std::vector<double> spread(n);
  for (std::size_t i = 0; i < n; ++i) {
    measures[0][i] = e(rng);
    measures[1][i] = u(rng) < 0.7 ? 0.0 : e(rng);
    measures[2][i] = std::floor(u(rng) * 90.0);
    spread[i] = u(rng);
  }
  const std::vector<std::vector<double>> weight_sets = {
      {}, std::vector<double>(n, 0.125), spread, std::vector<double>(n, 0.0)};
  for (std::size_t w = 0; w < weight_sets.size(); ++w) {
    for (int threads : {1, 2}) {
      const std::vector<Statistics> each = compute_statistics_of_each(
          {measures.begin(), measures.end()}, weight_sets[w], 16, threads);
      ASSERT_EQ(each.size(), measures.size());
      for (std::size_t m = 0; m < measures.size(); ++m) {
        const Statistics own = compute_statistics(measures[m], weight_sets[w], 16, threads);
        const Statistics& got = each[m];
        const std::string where = "weights " + std::to_string(w) + " threads " +
                                  std::to_string(threads) + " measure " + std::to_string(m);
        expect_same(got, own, where);
        EXPECT_EQ(got.area_weighted, w == 2) << where;
      }
    }
  }
  EXPECT_TRUE(compute_statistics_of_each({}, {}).empty());
}

// One weight shared by every sample, passed as a number: the statistics of a weights vector
// holding it once per sample, bit for bit (weight sums over full blocks and a partial one).
TEST(Statistics, OfEachWithOneEqualWeightEqualsItsVectorTwin) {
  std::mt19937_64 rng(11);
  std::exponential_distribution<double> e(3.0);
  for (const std::size_t n :
       {std::size_t{1}, std::size_t{1000}, kStatisticsBlock, 3 * kStatisticsBlock + 17}) {
    std::vector<std::vector<double>> measures(2, std::vector<double>(n));
    for (std::size_t i = 0; i < n; ++i) {
      measures[0][i] = e(rng);
      measures[1][i] = std::floor(e(rng) * 10.0);
    }
    const std::vector<ConstSpan<double>> spans(measures.begin(), measures.end());
    for (const double w : {0.0, 0.1, 0.125, 3.7e-6}) {
      for (int threads : {1, 2}) {
        const std::vector<Statistics> got = compute_statistics_of_each(spans, w, 16, threads);
        const std::vector<Statistics> twin =
            compute_statistics_of_each(spans, std::vector<double>(n, w), 16, threads);
        ASSERT_EQ(got.size(), twin.size());
        for (std::size_t m = 0; m < got.size(); ++m) {
          const std::string where = "n " + std::to_string(n) + " w " + std::to_string(w) +
                                    " threads " + std::to_string(threads) + " measure " +
                                    std::to_string(m);
          expect_same(got[m], twin[m], where);
        }
      }
    }
  }
}

// A cumulative weight that reaches q of the total exactly at the end of a bin: that bin's last
// value is the quantile (32 values, 2 bins; weights 0.5, 1.5, ... below 16, then 1).
TEST(Statistics, WeightedQuantileReachedExactlyAtABinsEnd) {
  std::vector<double> values, weights;
  for (int i = 0; i < 32; ++i) {
    values.push_back(i);
    weights.push_back(i < 16 ? (i % 2 == 0 ? 0.5 : 1.5) : 1.0);
  }
  const Statistics s = compute_statistics(values, weights);
  ASSERT_TRUE(s.area_weighted);
  EXPECT_EQ(s.p50, 15.0);  // cumulative weight 16 = 0.5 x 32 at value 15
}

TEST(Statistics, AllZeroWeightsFallBackToEqualWeights) {
  Statistics s = compute_statistics(std::vector<double>{1, 3}, {0, 0});
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
