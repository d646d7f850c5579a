#include "metric/statistics.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>
#include <utility>

namespace meshdev {
namespace {

// Neumaier's compensated summation: the sum of many small terms stays exact to ~1 ulp. Each
// step's rounding error comes from Knuth's branch-free TwoSum, which is exact for any order of
// magnitudes, so it equals the error of Neumaier's magnitude test (Fast2Sum on the larger
// operand) bit for bit, without the test's unpredictable branch.
class CompensatedSum {
 public:
  void add(double x) {
    const double t = sum_ + x;
    const double z = t - sum_;
    comp_ += (sum_ - (t - z)) + (x - z);
    sum_ = t;
  }
  double value() const { return sum_ + comp_; }

 private:
  double sum_ = 0.0, comp_ = 0.0;
};

// The quantiles qs[0..4) (ascending) of values in [lo, hi] with total weight `total`, into
// *outs[q]: with weights == nullptr the order statistics k = ceil(q n) - 1, else the smallest
// value whose cumulative weight (in ascending value order) reaches q total.
// Bins: one pass puts every value in one of up to 65,536 bins over [lo, hi]; bin_of is monotone
// in the value (a rounded difference, a positive scale, a truncation), so every value of a bin
// lies below every value of the next, and a quantile is found by counting (or summing weights)
// bin by bin and then selecting (or sorting) inside its bin only. O(n) plus the size of the
// quantiles' bins (all of n only when they hold nearly everything, e.g. a 0-heavy sample).
// The cumulative weight is summed bin by bin (compensated, then element by element inside the
// quantile's bin); it can differ from a sum in sorted order by an ulp, which matters only where
// it lies within an ulp of q total.
void quantiles(const std::vector<double>& values, const std::vector<double>* weights, double lo,
               double hi, double total, const double qs[4], double* outs[4]) {
  const std::size_t n = values.size();
  const int bins = static_cast<int>(std::clamp<std::size_t>(n / 16, 1, 65536));
  double scale = hi > lo ? bins / (hi - lo) : 0.0;
  if (!std::isfinite(scale)) scale = 0.0;  // a range of denormal width or beyond double: 1 bin
  auto bin_of = [&](double v) {
    const double t = (v - lo) * scale;  // in [0, bins]
    return t < bins - 1 ? static_cast<int>(t) : bins - 1;
  };
  // Each quantile's bin and what lies below it: a count, or a weight sum.
  int bin[4];
  std::size_t rank[4] = {};
  CompensatedSum below[4];
  if (weights == nullptr) {
    std::vector<std::size_t> count(static_cast<std::size_t>(bins), 0);
    for (double v : values) ++count[bin_of(v)];
    std::size_t b = 0, before = 0;
    for (int q = 0; q < 4; ++q) {
      const double r = std::ceil(qs[q] * static_cast<double>(n)) - 1.0;
      const auto k = static_cast<std::size_t>(std::clamp(r, 0.0, static_cast<double>(n - 1)));
      while (before + count[b] <= k) before += count[b++];
      bin[q] = static_cast<int>(b);
      rank[q] = k - before;
    }
  } else {
    std::vector<CompensatedSum> sum(static_cast<std::size_t>(bins));
    for (std::size_t i = 0; i < n; ++i) sum[bin_of(values[i])].add((*weights)[i]);
    for (int q = 0; q < 4; ++q) {
      const double target = qs[q] * total;
      CompensatedSum cum;
      int b = 0;
      for (; b < bins - 1; ++b) {
        CompensatedSum next = cum;
        next.add(sum[b].value());
        if (next.value() >= target) break;
        cum = next;
      }
      bin[q] = b;
      below[q] = cum;
    }
  }
  // The values (and weights) of the quantiles' bins, one pass.
  std::vector<int> slot(static_cast<std::size_t>(bins), -1);
  std::vector<std::vector<std::pair<double, double>>> held;
  for (int q = 0; q < 4; ++q)
    if (slot[bin[q]] < 0) {
      slot[bin[q]] = static_cast<int>(held.size());
      held.emplace_back();
    }
  for (std::size_t i = 0; i < n; ++i) {
    const int k = slot[bin_of(values[i])];
    if (k >= 0) held[k].push_back({values[i], weights != nullptr ? (*weights)[i] : 1.0});
  }
  for (int q = 0; q < 4; ++q) {
    std::vector<std::pair<double, double>>& h = held[slot[bin[q]]];
    assert(!h.empty());
    if (weights == nullptr) {
      std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(rank[q]), h.end());
      *outs[q] = h[rank[q]].first;
      continue;
    }
    // Sorting (value, weight) pairs: equal values give the same quantile in any order, so an
    // unstable sort is deterministic here.
    std::sort(h.begin(), h.end());
    const double target = qs[q] * total;
    CompensatedSum cum = below[q];
    *outs[q] = h.back().first;  // the bin's sum reached the target; its elements may round short
    for (const auto& [value, weight] : h) {
      cum.add(weight);
      if (cum.value() >= target) {
        *outs[q] = value;
        break;
      }
    }
  }
}

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
  quantiles(values, s.area_weighted ? &weights : nullptr, s.min, s.max, s.weight_sum, qs, outs);

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
