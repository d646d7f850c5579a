#include "metric/statistics.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>
#include <utility>

namespace meshdev {
namespace {

// Neumaier's compensated summation: the sum of many small terms stays exact to ~1 ulp.
class CompensatedSum {
 public:
  void add(double x) {
    const double t = sum_ + x;
    if (std::fabs(sum_) >= std::fabs(x))
      comp_ += (sum_ - t) + x;
    else
      comp_ += (x - t) + sum_;
    sum_ = t;
  }
  double value() const { return sum_ + comp_; }

 private:
  double sum_ = 0.0, comp_ = 0.0;
};

}  // namespace

Statistics compute_statistics(const std::vector<double>& values, const std::vector<double>& weights,
                              int histogram_bins) {
  assert(weights.empty() || weights.size() == values.size());
  Statistics s;
  s.count = values.size();
  if (values.empty()) return s;

  // Weights: uniform when absent or all zero.
  CompensatedSum wsum;
  bool uniform = weights.empty();
  if (!uniform) {
    for (double w : weights) wsum.add(w);
    uniform = !(wsum.value() > 0.0);
  }
  auto weight = [&](std::size_t i) { return uniform ? 1.0 : weights[i]; };
  s.weight_sum = uniform ? static_cast<double>(values.size()) : wsum.value();
  if (!uniform) {
    const double w0 = weights[0];
    s.area_weighted =
        std::any_of(weights.begin(), weights.end(), [w0](double w) { return w != w0; });
  }

  s.min = s.max = values[0];
  for (std::size_t i = 1; i < values.size(); ++i) {
    if (values[i] < s.min) {
      s.min = values[i];
      s.argmin = i;
    }
    if (values[i] > s.max) {
      s.max = values[i];
      s.argmax = i;
    }
  }

  CompensatedSum sum, sum_sq;
  for (std::size_t i = 0; i < values.size(); ++i) {
    sum.add(weight(i) * values[i]);
    sum_sq.add(weight(i) * values[i] * values[i]);
  }
  s.mean = sum.value() / s.weight_sum;
  s.rms = std::sqrt(std::max(0.0, sum_sq.value() / s.weight_sum));
  CompensatedSum var;
  for (std::size_t i = 0; i < values.size(); ++i)
    var.add(weight(i) * (values[i] - s.mean) * (values[i] - s.mean));
  s.variance = var.value() / s.weight_sum;
  s.stddev = std::sqrt(s.variance);

  // Weighted quantiles: the smallest value whose cumulative weight reaches q of the total.
  const double qs[4] = {0.50, 0.90, 0.95, 0.99};
  double* outs[4] = {&s.p50, &s.p90, &s.p95, &s.p99};
  if (!s.area_weighted) {
    // Equal weights: the quantile is the order statistic k = ceil(q n) - 1, found by selection
    // (O(n), ascending q on shrinking ranges) instead of a full sort.
    std::vector<double> scratch(values);
    const auto n = static_cast<double>(values.size());
    std::size_t from = 0;
    for (int q = 0; q < 4; ++q) {
      const double rank = std::ceil(qs[q] * n) - 1.0;
      const auto k = static_cast<std::size_t>(std::clamp(rank, 0.0, n - 1.0));
      std::nth_element(scratch.begin() + static_cast<std::ptrdiff_t>(from),
                       scratch.begin() + static_cast<std::ptrdiff_t>(k), scratch.end());
      *outs[q] = scratch[k];
      from = k;
    }
  } else {
    // Sorting (value, weight) pairs: equal values give the same quantile in any order, so an
    // unstable sort is deterministic here (and much faster than sorting indices).
    std::vector<std::pair<double, double>> sorted(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) sorted[i] = {values[i], weight(i)};
    std::sort(sorted.begin(), sorted.end());
    CompensatedSum cum;
    int q = 0;
    for (std::size_t k = 0; k < sorted.size() && q < 4; ++k) {
      cum.add(sorted[k].second);
      while (q < 4 && cum.value() >= qs[q] * s.weight_sum) *outs[q++] = sorted[k].first;
    }
    while (q < 4) *outs[q++] = s.max;
  }

  // Histogram over [min(0, min), max].
  const int bins = std::max(1, histogram_bins);
  const double lo = std::min(0.0, s.min), hi = s.max;
  Histogram& h = s.histogram;
  h.edges.resize(static_cast<std::size_t>(bins) + 1);
  for (int b = 0; b <= bins; ++b) h.edges[b] = lo + (hi - lo) * b / bins;
  h.counts.assign(static_cast<std::size_t>(bins), 0);
  std::vector<CompensatedSum> wbin(static_cast<std::size_t>(bins));
  for (std::size_t i = 0; i < values.size(); ++i) {
    int b = hi > lo ? static_cast<int>((values[i] - lo) / (hi - lo) * bins) : 0;
    b = std::clamp(b, 0, bins - 1);
    ++h.counts[b];
    wbin[b].add(weight(i));
  }
  h.weight_fraction.resize(static_cast<std::size_t>(bins));
  for (int b = 0; b < bins; ++b) h.weight_fraction[b] = wbin[b].value() / s.weight_sum;
  return s;
}

}  // namespace meshdev
