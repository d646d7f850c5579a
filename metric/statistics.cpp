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

// The quantiles' bins: up to 65,536 bins over [lo, hi]; bin_of is monotone in the value (a
// rounded difference, a positive scale, a truncation), so every value of a bin lies below every
// value of the next, and a quantile is found by counting (or summing weights) bin by bin and
// then selecting (or sorting) inside its bin only. Filled during the statistics' last full pass
// (add), then find() makes one more pass over the values of the quantiles' bins. O(n) plus the
// size of those bins (all of n only when they hold nearly everything, e.g. a 0-heavy sample).
class QuantileBins {
 public:
  QuantileBins(std::size_t n, double lo, double hi, bool weighted)
      : n_(n), lo_(lo), bins_(static_cast<int>(std::clamp<std::size_t>(n / 16, 1, 65536))) {
    scale_ = hi > lo ? bins_ / (hi - lo) : 0.0;
    if (!std::isfinite(scale_)) scale_ = 0.0;  // a range of denormal width or beyond double
    if (weighted)
      sum_.resize(static_cast<std::size_t>(bins_));
    else
      count_.resize(static_cast<std::size_t>(bins_), 0);
  }
  int bin_of(double v) const {
    const double t = (v - lo_) * scale_;  // in [0, bins]
    return t < bins_ - 1 ? static_cast<int>(t) : bins_ - 1;
  }
  void count(double v) { ++count_[bin_of(v)]; }
  void add(double v, double w) { sum_[bin_of(v)].add(w); }

  // The quantiles qs[0..4) (ascending) into *outs[q]: unweighted, the order statistics
  // k = ceil(q n) - 1; weighted, the smallest value whose cumulative weight (in ascending value
  // order) reaches q total. The cumulative weight is summed bin by bin (compensated, then
  // element by element inside the quantile's bin); it can differ from a sum in sorted order by
  // an ulp, which matters only where it lies within an ulp of q total.
  void find(const std::vector<double>& values, const double* weights, double total,
            const double qs[4], double* outs[4]) const {
    int bin[4];
    std::size_t rank[4] = {};
    CompensatedSum below[4];
    if (weights == nullptr) {
      std::size_t b = 0, before = 0;
      for (int q = 0; q < 4; ++q) {
        const double r = std::ceil(qs[q] * static_cast<double>(n_)) - 1.0;
        const auto k = static_cast<std::size_t>(std::clamp(r, 0.0, static_cast<double>(n_ - 1)));
        while (before + count_[b] <= k) before += count_[b++];
        bin[q] = static_cast<int>(b);
        rank[q] = k - before;
      }
    } else {
      for (int q = 0; q < 4; ++q) {
        const double target = qs[q] * total;
        CompensatedSum cum;
        int b = 0;
        for (; b < bins_ - 1; ++b) {
          CompensatedSum next = cum;
          next.add(sum_[b].value());
          if (next.value() >= target) break;
          cum = next;
        }
        bin[q] = b;
        below[q] = cum;
      }
    }
    if (weights == nullptr) {
      select_in_bins(values, bin, rank, outs);
      return;
    }
    // The values and weights of the quantiles' bins, one pass; the values equal to the minimum
    // lo_ (all in bin 0; often most of the sample, the exact zeros of coplanar parts) are not
    // kept, only their weight summed (compensated, in sample order: it can differ from their sum
    // in sorted order by an ulp, as the bins' sums can).
    std::vector<int> slot(static_cast<std::size_t>(bins_), -1);
    std::vector<std::vector<std::pair<double, double>>> held;
    for (int q = 0; q < 4; ++q)
      if (slot[bin[q]] < 0) {
        slot[bin[q]] = static_cast<int>(held.size());
        held.emplace_back();
      }
    CompensatedSum at_lo;
    for (std::size_t i = 0; i < n_; ++i) {
      const double v = values[i];
      const int k = slot[bin_of(v)];
      if (k < 0) continue;
      if (v == lo_)
        at_lo.add(weights[i]);
      else
        held[k].push_back({v, weights[i]});
    }
    std::vector<bool> sorted(held.size(), false);
    for (int q = 0; q < 4; ++q) {
      const double target = qs[q] * total;
      CompensatedSum cum = below[q];
      std::vector<std::pair<double, double>>& h = held[slot[bin[q]]];
      if (bin[q] == 0) {
        cum.add(at_lo.value());
        if (cum.value() >= target || h.empty()) {
          *outs[q] = lo_;  // (empty: the bin's sum reached the target; its values round short)
          continue;
        }
      }
      assert(!h.empty());
      // Sorting (value, weight) pairs: equal values give the same quantile in any order, so an
      // unstable sort is deterministic here.
      if (!sorted[slot[bin[q]]]) std::sort(h.begin(), h.end());
      sorted[slot[bin[q]]] = true;
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

 private:
  // Unweighted: the value of rank rank[q] in bin bin[q], for each q. One pass gathers the values
  // of those bins, except the minimum lo_, which is only counted: bin 0 often holds most of the
  // sample and most of it at the minimum (the exact zeros of coplanar parts), and a rank below
  // that count is the minimum itself. Then a selection per bin among the rest.
  void select_in_bins(const std::vector<double>& values, const int bin[4],
                      const std::size_t rank[4], double* outs[4]) const {
    std::vector<int> slot(static_cast<std::size_t>(bins_), -1);
    std::vector<std::vector<double>> held;
    for (int q = 0; q < 4; ++q)
      if (slot[bin[q]] < 0) {
        slot[bin[q]] = static_cast<int>(held.size());
        held.emplace_back().reserve(count_[bin[q]]);
      }
    std::size_t at_lo = 0;
    for (std::size_t i = 0; i < n_; ++i) {
      const double v = values[i];
      const int k = slot[bin_of(v)];
      if (k < 0) continue;
      if (v == lo_)
        ++at_lo;  // only in bin 0
      else
        held[k].push_back(v);
    }
    for (int q = 0; q < 4; ++q) {
      if (bin[q] == 0 && rank[q] < at_lo) {
        *outs[q] = lo_;
        continue;
      }
      const std::size_t r = bin[q] == 0 ? rank[q] - at_lo : rank[q];
      std::vector<double>& h = held[slot[bin[q]]];
      assert(r < h.size());
      std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(r), h.end());
      *outs[q] = h[r];
    }
  }

  std::size_t n_;
  double lo_, scale_ = 0.0;
  int bins_;
  std::vector<std::size_t> count_;
  std::vector<CompensatedSum> sum_;
};

// The passes over the values, for a weight function (all 1, or the given weights); the moments'
// sums are compensated and taken in sample order. area_weights: the weights if they differ
// (weighted quantiles and histogram shares), else nullptr.
template <typename Weight>
void fill(const std::vector<double>& values, Weight weight, const double* area_weights,
          int histogram_bins, Statistics& s) {
  const bool area_weighted = area_weights != nullptr;
  const std::size_t n = values.size();
  // Pass 1: extremes and the first two moments.
  s.min = s.max = values[0];
  CompensatedSum sum, sum_sq;
  for (std::size_t i = 0; i < n; ++i) {
    const double v = values[i];
    if (v < s.min) {
      s.min = v;
      s.argmin = i;
    }
    if (v > s.max) {
      s.max = v;
      s.argmax = i;
    }
    sum.add(weight(i) * v);
    sum_sq.add(weight(i) * v * v);
  }
  s.mean = sum.value() / s.weight_sum;
  s.rms = std::sqrt(std::max(0.0, sum_sq.value() / s.weight_sum));

  // Pass 2: the variance, the histogram over [min(0, min), max] and the quantiles' bins.
  const int bins = std::max(1, histogram_bins);
  const double lo = std::min(0.0, s.min), hi = s.max;
  Histogram& h = s.histogram;
  h.edges.resize(static_cast<std::size_t>(bins) + 1);
  for (int b = 0; b <= bins; ++b) h.edges[b] = lo + (hi - lo) * b / bins;
  h.counts.assign(static_cast<std::size_t>(bins), 0);
  std::vector<CompensatedSum> wbin(area_weighted ? static_cast<std::size_t>(bins) : 0);
  QuantileBins quantile_bins(n, s.min, s.max, area_weighted);
  CompensatedSum var;
  for (std::size_t i = 0; i < n; ++i) {
    const double v = values[i];
    var.add(weight(i) * (v - s.mean) * (v - s.mean));
    int b = hi > lo ? static_cast<int>((v - lo) / (hi - lo) * bins) : 0;
    b = std::clamp(b, 0, bins - 1);
    ++h.counts[b];
    if (area_weighted) {
      wbin[b].add(weight(i));
      quantile_bins.add(v, weight(i));
    } else {
      quantile_bins.count(v);
    }
  }
  s.variance = var.value() / s.weight_sum;
  s.stddev = std::sqrt(s.variance);

  // Equal weights: each bin's share is its count's (exactly, without summing weights).
  h.weight_fraction.resize(static_cast<std::size_t>(bins));
  for (int b = 0; b < bins; ++b) {
    if (!area_weighted) {
      h.weight_fraction[b] = static_cast<double>(h.counts[b]) / static_cast<double>(n);
      continue;
    }
    h.weight_fraction[b] = wbin[b].value() / s.weight_sum;
  }

  // Weighted quantiles: the smallest value whose cumulative weight reaches q of the total.
  const double qs[4] = {0.50, 0.90, 0.95, 0.99};
  double* outs[4] = {&s.p50, &s.p90, &s.p95, &s.p99};
  quantile_bins.find(values, area_weights, s.weight_sum, qs, outs);
}

}  // namespace

Statistics compute_statistics(const std::vector<double>& values, const std::vector<double>& weights,
                              int histogram_bins) {
  assert(weights.empty() || weights.size() == values.size());
  Statistics s;
  s.count = values.size();
  if (values.empty()) return s;

  // Weights: uniform when absent or all zero; area-weighted when they differ.
  bool uniform = weights.empty();
  if (!uniform) {
    CompensatedSum wsum;
    bool differ = false;
    const double w0 = weights[0];
    for (double w : weights) {
      wsum.add(w);
      differ |= w != w0;
    }
    uniform = !(wsum.value() > 0.0);
    s.weight_sum = wsum.value();
    s.area_weighted = !uniform && differ;
  }
  if (uniform) {
    s.weight_sum = static_cast<double>(values.size());
    fill(
        values, [](std::size_t) { return 1.0; }, nullptr, histogram_bins, s);
  } else {
    fill(
        values, [&weights](std::size_t i) { return weights[i]; },
        s.area_weighted ? weights.data() : nullptr, histogram_bins, s);
  }
  return s;
}

}  // namespace meshdev
