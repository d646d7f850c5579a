#pragma once
// Summary statistics of per-sample deviations, optionally weighted (area weights of face
// samples). Deterministic: compensated sums taken in sample order inside fixed blocks of
// kStatisticsBlock values and merged in block order, so the result depends neither on the thread
// count that produced the values nor on the one that summarises them.
#include <cstddef>
#include <vector>

#include "metric/value_span.h"

namespace meshdev {

struct Histogram {
  std::vector<double> edges;            // bins+1 edges from 0 (or min if negative) to max
  std::vector<std::size_t> counts;      // samples per bin (last bin closed on the right)
  std::vector<double> weight_fraction;  // share of the total weight per bin
};

struct Statistics {
  std::size_t count = 0;       // number of samples
  double weight_sum = 0;       // total weight behind mean/variance/percentiles (area for faces)
  bool area_weighted = false;  // false: every sample counted equally
  double min = 0, max = 0;     // over every sample, zero-weight ones included
  double mean = 0, variance = 0, stddev = 0, rms = 0;  // weighted; population variance
  double p50 = 0, p90 = 0, p95 = 0, p99 = 0;           // weighted quantiles (lower value)
  std::size_t argmin = 0, argmax = 0;                  // first sample index reaching min / max
  Histogram histogram;
};

// Values per block of the passes (a block's sums are taken in sample order; blocks run on the
// threads and are merged in block order).
constexpr std::size_t kStatisticsBlock = std::size_t{1} << 15;

// Statistics of `values` with `weights` (empty = all 1). Samples with weight 0 count for min, max
// and the histogram counts only. If every weight is 0, all samples are weighted equally.
// threads: the OpenMP team for the passes (0 = OpenMP's default; a set of one block runs on
// the calling thread); the result is the same for every team size.
// Precondition: weights empty or the same size as values, weights >= 0. O(n) (quantiles: a
// histogram pass, then selection inside the quantiles' bins; O(n log n) only if they hold most
// values); about 3 passes over the values plus, for area weights, one over their quantile bins.
Statistics compute_statistics(ConstSpan<double> values, const std::vector<double>& weights,
                              int histogram_bins = 32, int threads = 1);

// compute_statistics of each of several measures' values over the same samples and weights (each
// the size of `weights`, or weights empty), the weights checked once. O(n) per measure.
std::vector<Statistics> compute_statistics_of_each(const std::vector<ConstSpan<double>>& values,
                                                   const std::vector<double>& weights,
                                                   int histogram_bins = 32, int threads = 1);

// compute_statistics_of_each with every sample weighing `equal_weight` (>= 0; what Monte Carlo
// sampling gives): the same result, bit for bit, as a weights vector holding it once per sample,
// without making or reading one. O(n) per measure.
std::vector<Statistics> compute_statistics_of_each(const std::vector<ConstSpan<double>>& values,
                                                   double equal_weight, int histogram_bins = 32,
                                                   int threads = 1);

}  // namespace meshdev
