#include "metric/statistics.h"

#include <omp.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <utility>

#include "metric/simd2.h"

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
  // No term added, or only zeros.
  bool empty() const { return sum_ == 0.0 && comp_ == 0.0; }
  // Adds another sum's terms (its running sum, then its compensation).
  void merge(const CompensatedSum& o) {
    add(o.sum_);
    add(o.comp_);
  }

 private:
  friend class CompensatedSumPair;
  double sum_ = 0.0, comp_ = 0.0;
};

// Two compensated sums in the two lanes of SSE2 registers (metric/simd2.h): each lane takes
// CompensatedSum::add's operations in its order, so lane k ends bit for bit where a
// CompensatedSum given lane k's terms would, at half the instructions. Pass 1's sum and sum of
// squares are two such sums over the same samples; the adds' throughput, not their latency, was
// what bounded it.
class CompensatedSumPair {
 public:
  void add(simd::D2 x) {
    const simd::D2 t = sum_ + x;
    const simd::D2 z = t - sum_;
    comp_ = comp_ + ((sum_ - (t - z)) + (x - z));
    sum_ = t;
  }
  // Lane k as a CompensatedSum.
  CompensatedSum lane(int k) const {
    double sum[2], comp[2];
    simd::store(sum, sum_);
    simd::store(comp, comp_);
    CompensatedSum s;
    s.sum_ = sum[k];
    s.comp_ = comp[k];
    return s;
  }

 private:
  simd::D2 sum_ = simd::D2::splat(0.0), comp_ = simd::D2::splat(0.0);
};

// The passes cut the values into blocks of kStatisticsBlock, run the blocks on the team and
// combine their partial results in block order (sums merged, extremes compared with the earlier
// block winning ties, integer counts added), so the result does not depend on the team's size.
std::size_t block_count(std::size_t n) {
  return (n + kStatisticsBlock - 1) / kStatisticsBlock;
}
std::size_t block_begin(std::int64_t b) {
  return static_cast<std::size_t>(b) * kStatisticsBlock;
}
std::size_t block_end(std::int64_t b, std::size_t n) {
  return std::min(n, block_begin(b) + kStatisticsBlock);
}
int team_size(int threads, std::size_t blocks) {
  const int wanted = threads > 0 ? threads : omp_get_max_threads();
  return static_cast<int>(std::clamp<std::size_t>(blocks, 1, static_cast<std::size_t>(wanted)));
}

// The quantiles' bins: up to 65,535 bins over [lo, hi]; bin_of is monotone in the value (a
// rounded difference, a positive scale, a truncation), so every value of a bin lies below every
// value of the next, and a quantile is found by counting (or summing weights) bin by bin and
// then selecting (or sorting) inside its bin only. Filled during the statistics' pass 2 (the
// threads' counts by add_counts; weights by sum_weights from the bins noted in pass 2), then find()
// makes one more pass over the values of the quantiles' bins. O(n) plus the
// size of those bins (all of n only when they hold nearly everything, e.g. a 0-heavy sample).
// Weighted, the values equal to the minimum lo (often most of the sample: the exact zeros of
// coplanar parts) are not binned: their weight is summed apart, per block of pass 2, and comes
// before bin 0's in the cumulative weight.
class QuantileBins {
 public:
  // sum_weights' stripes of samples: a constant, so that the sums do not depend on the team.
  static constexpr int kStripes = 4;
  // sum_weights' spare sums, past the bins, where the weights of values at the minimum go so
  // that no branch skips them; they are not read (pass 2 sums those weights per block).
  static constexpr std::size_t kSpares = 4;

  QuantileBins(std::size_t n, double lo, double hi, bool weighted)
      : n_(n), lo_(lo), bins_(static_cast<int>(std::clamp<std::size_t>(n / 16, 1, 65535))) {
    scale_ = hi > lo ? bins_ / (hi - lo) : 0.0;
    if (!std::isfinite(scale_)) scale_ = 0.0;  // a range of denormal width or beyond double
    if (!weighted) count_.resize(static_cast<std::size_t>(bins_), 0);  // weighted: sum_weights
  }
  int bin_of(double v) const {
    const double t = (v - lo_) * scale_;  // in [0, bins]
    return t < bins_ - 1 ? static_cast<int>(t) : bins_ - 1;
  }
  int size() const { return bins_; }
  // Weighted: bin_of(v), or the number of bins (one past the last bin: at most 65,535, so a code
  // fits 16 bits) for a value at the minimum (bin_at, sum_weights, find). Without a branch:
  // values at the minimum come and go at random on some samples.
  std::uint16_t code_of(double v) const {
    const auto bin = static_cast<unsigned>(bin_of(v));
    const unsigned at_lo = 0u - static_cast<unsigned>(v == lo_);  // all ones or zero
    return static_cast<std::uint16_t>(bin ^ ((bin ^ static_cast<unsigned>(bins_)) & at_lo));
  }
  // Weighted: the total weight of the values at the minimum (their blocks' sums merged in block
  // order by the caller).
  void set_at_minimum(const CompensatedSum& sum) { at_lo_ = sum; }
  // Adds one thread's counts (per bin, in bin order) to the bins'.
  void add_counts(const std::vector<std::size_t>& counts) {
    for (int b = 0; b < bins_; ++b) count_[b] += counts[b];
  }
  // The bins' weight sums, from pass 2's codes (bin_at[i] = code_of(values[i]): 2 bytes read
  // per sample instead of the value, whose bin would be computed again). The samples are cut into
  // kStripes fixed stripes, dealt out to the team; each stripe sums its weights per bin in sample
  // order, and the stripes' sums are merged bin by bin in stripe order, so every bin's sum is the
  // same whatever the team size, and every thread has work however the sample crowds into the
  // bins (a range of bins per thread left most of it to the first). O(n / team + kStripes bins).
  void sum_weights(const std::uint16_t* bin_at, const double* weights, int team) {
    std::vector<std::vector<CompensatedSum>> part(kStripes - 1);
#pragma omp parallel for num_threads(team) schedule(static, 1) if (team > 1)
    for (int j = 0; j < kStripes; ++j) {
      // Without a branch per sample (where values at the minimum come and go at random it
      // missed often): their code is the first spare sum's index, and sample i's weight goes to
      // spare i mod kSpares, so that consecutive ones do not wait for each other's store.
      std::vector<CompensatedSum>& into = j == 0 ? sum_ : part[j - 1];
      into.resize(static_cast<std::size_t>(bins_) + kSpares);
      const std::size_t end = n_ * static_cast<std::size_t>(j + 1) / kStripes;
      for (std::size_t i = n_ * static_cast<std::size_t>(j) / kStripes; i < end; ++i) {
        const std::size_t k = bin_at[i];
        const std::size_t at_lo =
            0 - static_cast<std::size_t>(k == static_cast<std::size_t>(bins_));
        into[k + (i % kSpares & at_lo)].add(weights[i]);
      }
    }
    // Stripe by stripe into the first's sums; an empty bin's (exact zeros) changes nothing.
    const auto bins = static_cast<std::int64_t>(bins_);
#pragma omp parallel for num_threads(team) schedule(static) if (team > 1)
    for (std::int64_t b = 0; b < bins; ++b)
      for (const std::vector<CompensatedSum>& stripe : part)
        if (!stripe[b].empty()) sum_[b].merge(stripe[b]);
  }

  // The quantiles qs[0..4) (ascending) into *outs[q]: unweighted, the order statistics
  // k = ceil(q n) - 1; weighted, the smallest value whose cumulative weight (in ascending value
  // order) reaches q total. The cumulative weight is summed bin by bin (compensated, then
  // element by element inside the quantile's bin); it can differ from a sum in sorted order by
  // an ulp, which matters only where it lies within an ulp of q total. bin_at: pass 2's codes
  // (code_of; weighted only).
  void find(ConstSpan<double> values, const double* weights, double total, const double qs[4],
            double* outs[4], int team, const std::uint16_t* bin_at) const {
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
      // One walk over the bins for the four (ascending) quantiles: the cumulative weight starts
      // with the values at the minimum (bin -1: the quantile is the minimum itself); a quantile's
      // bin is the first whose cumulative weight reaches its target, else the last bin.
      CompensatedSum cum = at_lo_;
      int q = 0;
      for (; q < 4 && cum.value() >= qs[q] * total; ++q) bin[q] = -1;
      for (int b = 0; q < 4; ++b) {
        CompensatedSum next = cum;
        next.add(sum_[b].value());
        for (; q < 4 && (b == bins_ - 1 || next.value() >= qs[q] * total); ++q) {
          bin[q] = b;
          below[q] = cum;
        }
        cum = next;
      }
    }
    if (weights == nullptr) {
      select_in_bins(values, bin, rank, outs, team);
      return;
    }
    // The values and weights of the quantiles' bins (the values at the minimum are in none),
    // one pass over pass 2's codes. The pairs are sorted below, so the order the threads gather
    // them in does not matter.
    assert(bin_at != nullptr);
    const std::vector<int> slot = slots_of(bin);
    using Pairs = std::vector<std::pair<double, double>>;
    std::vector<Pairs> held;
    if (std::any_of(bin, bin + 4, [](int b) { return b >= 0; })) {
      held = gather<Pairs>(slot, team, [&](std::int64_t b, std::vector<Pairs>& mine) {
        for (std::size_t i = block_begin(b); i < block_end(b, n_); ++i) {
          const int k = slot[bin_at[i]];
          if (k >= 0) mine[k].push_back({values[i], weights[i]});
        }
      });
    }
    std::vector<bool> sorted(held.size(), false);
    for (int q = 0; q < 4; ++q) {
      if (bin[q] < 0) {
        *outs[q] = lo_;
        continue;
      }
      const double target = qs[q] * total;
      CompensatedSum cum = below[q];
      Pairs& h = held[slot[bin[q]]];
      if (h.empty()) {  // the last bin, reached without its target (the sums round short), empty
        *outs[q] = lo_;
        continue;
      }
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
  // slot[b]: the index of bin b among the quantiles' distinct bins (bin -1, the minimum, has
  // none), -1 for the other bins and for code_of's code of the minimum (the last entry).
  std::vector<int> slots_of(const int bin[4]) const {
    std::vector<int> slot(static_cast<std::size_t>(bins_) + 1, -1);
    int slots = 0;
    for (int q = 0; q < 4; ++q)
      if (bin[q] >= 0 && slot[bin[q]] < 0) slot[bin[q]] = slots++;
    return slot;
  }

  // What the blocks keep of the quantiles' bins, one Held per distinct bin: scan(b, mine) keeps
  // block b's values in the calling thread's own Helds, which are then joined in thread order.
  template <class Held, class Scan>
  std::vector<Held> gather(const std::vector<int>& slot, int team, Scan scan) const {
    const std::size_t slots =
        static_cast<std::size_t>(*std::max_element(slot.begin(), slot.end()) + 1);
    std::vector<std::vector<Held>> per_thread(static_cast<std::size_t>(team));
    const auto blocks = static_cast<std::int64_t>(block_count(n_));
#pragma omp parallel num_threads(team) if (team > 1)
    {
      std::vector<Held> mine(slots);
#pragma omp for schedule(static)
      for (std::int64_t b = 0; b < blocks; ++b) scan(b, mine);
      per_thread[static_cast<std::size_t>(omp_get_thread_num())] = std::move(mine);
    }
    std::vector<Held> held = std::move(per_thread[0]);
    for (std::size_t t = 1; t < per_thread.size(); ++t)
      for (std::size_t k = 0; k < per_thread[t].size(); ++k)
        held[k].insert(held[k].end(), per_thread[t][k].begin(), per_thread[t][k].end());
    return held;
  }

  // Unweighted: the value of rank rank[q] in bin bin[q], for each q. One pass gathers the values
  // of those bins, except the minimum lo_, which is only counted: bin 0 often holds most of the
  // sample and most of it at the minimum (the exact zeros of coplanar parts), and a rank below
  // that count is the minimum itself. Then a selection per bin among the rest (the k-th value
  // does not depend on the order the threads gathered them in).
  void select_in_bins(ConstSpan<double> values, const int bin[4], const std::size_t rank[4],
                      double* outs[4], int team) const {
    const std::vector<int> slot = slots_of(bin);
    std::vector<std::size_t> at_lo_part(block_count(n_), 0);
    auto held = gather<std::vector<double>>(
        slot, team, [&](std::int64_t b, std::vector<std::vector<double>>& mine) {
          std::size_t at_lo = 0;
          for (std::size_t i = block_begin(b); i < block_end(b, n_); ++i) {
            const double v = values[i];
            const int k = slot[bin_of(v)];
            if (k < 0) continue;
            if (v == lo_)
              ++at_lo;  // only in bin 0
            else
              mine[k].push_back(v);
          }
          at_lo_part[b] = at_lo;
        });
    const std::size_t at_lo = std::accumulate(at_lo_part.begin(), at_lo_part.end(), std::size_t{0});
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
  CompensatedSum at_lo_;  // weighted: the weight of the values at the minimum
};

// The passes over the values, for a weight function (all 1, or the given weights); the moments'
// sums are compensated, taken in sample order inside each block and merged in block order.
// area_weights: the weights if they differ (weighted quantiles and histogram shares), else
// nullptr. team: the threads that run the blocks.
template <typename Weight>
void fill(ConstSpan<double> values, Weight weight, const double* area_weights, int histogram_bins,
          int team, Statistics& s) {
  const bool area_weighted = area_weights != nullptr;
  constexpr std::size_t kWays = 4;  // weighted histogram: interleaved sums per bin (pass 2)
  const std::size_t n = values.size();
  const auto blocks = static_cast<std::int64_t>(block_count(n));

  // Pass 1: extremes and the first two moments.
  struct Moments {
    double min, max;
    std::size_t argmin, argmax;
    CompensatedSum sum, sum_sq;
  };
  std::vector<Moments> moments(static_cast<std::size_t>(blocks));
#pragma omp parallel for num_threads(team) schedule(static) if (team > 1)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const std::size_t begin = block_begin(b);
    Moments m{values[begin], values[begin], begin, begin, {}, {}};
    CompensatedSumPair sums;  // lane 0: sum, lane 1: sum_sq
    for (std::size_t i = begin; i < block_end(b, n); ++i) {
      const double v = values[i];
      if (v < m.min) {
        m.min = v;
        m.argmin = i;
      }
      if (v > m.max) {
        m.max = v;
        m.argmax = i;
      }
      const double wv = weight(i) * v;  // weight(i) * v * v below: (w v) v, as before
      sums.add(simd::D2::pair(wv, wv * v));
    }
    m.sum = sums.lane(0);
    m.sum_sq = sums.lane(1);
    moments[b] = m;
  }
  Moments all = moments[0];
  for (std::size_t b = 1; b < moments.size(); ++b) {
    const Moments& m = moments[b];
    if (m.min < all.min) {
      all.min = m.min;
      all.argmin = m.argmin;
    }
    if (m.max > all.max) {
      all.max = m.max;
      all.argmax = m.argmax;
    }
    all.sum.merge(m.sum);
    all.sum_sq.merge(m.sum_sq);
  }
  s.min = all.min;
  s.max = all.max;
  s.argmin = all.argmin;
  s.argmax = all.argmax;
  s.mean = all.sum.value() / s.weight_sum;
  s.rms = std::sqrt(std::max(0.0, all.sum_sq.value() / s.weight_sum));

  // Pass 2: the variance, the histogram over [min(0, min), max] and the quantiles' bins (counts
  // per thread, added; weight sums per block for the histogram, by ranges of bins for the
  // quantiles).
  const int bins = std::max(1, histogram_bins);
  const auto nbins = static_cast<std::size_t>(bins);
  const double lo = std::min(0.0, s.min), hi = s.max;
  Histogram& h = s.histogram;
  h.edges.resize(nbins + 1);
  for (int b = 0; b <= bins; ++b) h.edges[b] = lo + (hi - lo) * b / bins;
  h.counts.assign(nbins, 0);
  QuantileBins quantile_bins(n, s.min, s.max, area_weighted);
  // Each sample's code_of (its quantile bin, or the minimum's code), for sum_weights and find.
  std::unique_ptr<std::uint16_t[]> bin_at(area_weighted ? new std::uint16_t[n] : nullptr);
  std::vector<CompensatedSum> var_part(static_cast<std::size_t>(blocks));
  std::vector<CompensatedSum> at_lo_part(area_weighted ? var_part.size() : 0);
  std::vector<CompensatedSum> wbin_part(area_weighted ? moments.size() * kWays * nbins : 0);
  std::vector<std::vector<std::size_t>> hist_of(static_cast<std::size_t>(team));
  std::vector<std::vector<std::size_t>> quantile_counts_of(static_cast<std::size_t>(team));
#pragma omp parallel num_threads(team) if (team > 1)
  {
    std::vector<std::size_t> hist(nbins, 0);
    std::vector<std::size_t> hist_ways(area_weighted ? kWays * nbins : 0, 0);
    std::vector<std::size_t> quantile_counts(
        area_weighted ? 0 : static_cast<std::size_t>(quantile_bins.size()), 0);
#pragma omp for schedule(static)
    for (std::int64_t blk = 0; blk < blocks; ++blk) {
      CompensatedSumPair sums;  // lane 0: the variance's sum; 1: the weight at the minimum
      CompensatedSum* wbin =
          area_weighted ? &wbin_part[static_cast<std::size_t>(blk) * kWays * nbins] : nullptr;
      // Weighted: sample i's histogram count and weight go to way i mod kWays of its bin (the
      // ways are added up after the pass, the weights' sums merged in way order): consecutive
      // samples mostly share a bin, and each sample's compensated add waited for the one before
      // on the same address (its load, four dependent adds, its store).
      for (std::size_t i = block_begin(blk); i < block_end(blk, n); ++i) {
        const double v = values[i];
        // The weight at the minimum without a branch (w x 1 = w, w x 0 = +0, and adding +0
        // leaves the sum's bits); 0 unweighted.
        const double at_lo = area_weighted ? static_cast<double>(v == s.min) * weight(i) : 0.0;
        sums.add(simd::D2::pair(weight(i) * (v - s.mean) * (v - s.mean), at_lo));
        int b = hi > lo ? static_cast<int>((v - lo) / (hi - lo) * bins) : 0;
        b = std::clamp(b, 0, bins - 1);
        if (!area_weighted) {
          ++hist[b];
          ++quantile_counts[quantile_bins.bin_of(v)];
          continue;
        }
        const std::size_t way = i % kWays;
        ++hist_ways[way * nbins + static_cast<std::size_t>(b)];
        wbin[way * nbins + static_cast<std::size_t>(b)].add(weight(i));
        bin_at[i] = quantile_bins.code_of(v);
      }
      var_part[blk] = sums.lane(0);
      if (area_weighted) at_lo_part[static_cast<std::size_t>(blk)] = sums.lane(1);
    }
    for (std::size_t k = 0; k < hist_ways.size(); ++k) hist[k % nbins] += hist_ways[k];
    const auto me = static_cast<std::size_t>(omp_get_thread_num());
    hist_of[me] = std::move(hist);
    quantile_counts_of[me] = std::move(quantile_counts);
  }
  CompensatedSum var;
  for (const CompensatedSum& part : var_part) var.merge(part);
  s.variance = var.value() / s.weight_sum;
  s.stddev = std::sqrt(s.variance);
  for (std::size_t t = 0; t < hist_of.size(); ++t) {
    if (hist_of[t].empty()) continue;  // a thread the team did not get
    for (std::size_t b = 0; b < nbins; ++b) h.counts[b] += hist_of[t][b];
    if (!area_weighted) quantile_bins.add_counts(quantile_counts_of[t]);
  }
  if (area_weighted) {
    quantile_bins.sum_weights(bin_at.get(), area_weights, team);
    CompensatedSum at_lo;
    for (const CompensatedSum& part : at_lo_part) at_lo.merge(part);
    quantile_bins.set_at_minimum(at_lo);
  }

  // Equal weights: each bin's share is its count's (exactly, without summing weights).
  h.weight_fraction.resize(nbins);
  for (std::size_t b = 0; b < nbins; ++b) {
    if (!area_weighted) {
      h.weight_fraction[b] = static_cast<double>(h.counts[b]) / static_cast<double>(n);
      continue;
    }
    CompensatedSum share;
    for (std::size_t blk = 0; blk < moments.size(); ++blk)
      for (std::size_t way = 0; way < kWays; ++way)
        share.merge(wbin_part[(blk * kWays + way) * nbins + b]);
    h.weight_fraction[b] = share.value() / s.weight_sum;
  }

  // Weighted quantiles: the smallest value whose cumulative weight reaches q of the total.
  const double qs[4] = {0.50, 0.90, 0.95, 0.99};
  double* outs[4] = {&s.p50, &s.p90, &s.p95, &s.p99};
  quantile_bins.find(values, area_weights, s.weight_sum, qs, outs, team, bin_at.get());
}

// What the statistics need to know of the weights: uniform (absent or all zero: every sample
// counts 1), equal (every weight is w0), their compensated sum. One blocked pass.
struct WeightCheck {
  bool uniform = true, equal = true;
  double w0 = 1.0, sum = 0.0;
};
WeightCheck check_weights(const std::vector<double>& weights, int team) {
  WeightCheck c;
  if (weights.empty()) return c;
  const std::size_t blocks = block_count(weights.size());
  std::vector<CompensatedSum> sum_part(blocks);
  std::vector<char> differ_part(blocks, 0);
  const double w0 = weights[0];
#pragma omp parallel for num_threads(team) schedule(static) if (team > 1)
  for (std::int64_t b = 0; b < static_cast<std::int64_t>(blocks); ++b) {
    CompensatedSum sum;
    bool differ = false;
    for (std::size_t i = block_begin(b); i < block_end(b, weights.size()); ++i) {
      sum.add(weights[i]);
      differ |= weights[i] != w0;
    }
    sum_part[b] = sum;
    differ_part[b] = differ;
  }
  CompensatedSum wsum;
  for (const CompensatedSum& part : sum_part) wsum.merge(part);
  c.sum = wsum.value();
  c.uniform = !(c.sum > 0.0);
  c.equal = std::find(differ_part.begin(), differ_part.end(), 1) == differ_part.end();
  c.w0 = w0;
  return c;
}

// check_weights of n weights all equal to w, without reading them: every full block holds the
// same terms, so its compensated sum is taken once and merged as often as check_weights merges
// the blocks' sums (the same result bit for bit). O(kStatisticsBlock).
WeightCheck equal_weights(double w, std::size_t n) {
  WeightCheck c;
  if (n == 0) return c;
  auto block_sum = [w](std::size_t count) {
    CompensatedSum sum;
    for (std::size_t i = 0; i < count; ++i) sum.add(w);
    return sum;
  };
  const std::size_t blocks = block_count(n);
  const CompensatedSum full = block_sum(kStatisticsBlock);
  CompensatedSum wsum;
  for (std::size_t b = 0; b + 1 < blocks; ++b) wsum.merge(full);
  wsum.merge(block_sum(block_end(static_cast<std::int64_t>(blocks - 1), n) -
                       block_begin(static_cast<std::int64_t>(blocks - 1))));
  c.sum = wsum.value();
  c.uniform = !(c.sum > 0.0);
  c.w0 = w;
  return c;
}

Statistics statistics_with(ConstSpan<double> values, const std::vector<double>& weights,
                           const WeightCheck& c, int histogram_bins, int team) {
  assert(weights.empty() || weights.size() == values.size());
  Statistics s;
  s.count = values.size();
  if (values.empty()) return s;
  if (c.uniform) {
    s.weight_sum = static_cast<double>(values.size());
    fill(
        values, [](std::size_t) { return 1.0; }, nullptr, histogram_bins, team, s);
    return s;
  }
  s.weight_sum = c.sum;
  s.area_weighted = !c.equal;
  if (c.equal) {  // every weight is w0: the same products without reading the weights
    fill(
        values, [w0 = c.w0](std::size_t) { return w0; }, nullptr, histogram_bins, team, s);
  } else {
    fill(
        values, [&weights](std::size_t i) { return weights[i]; }, weights.data(), histogram_bins,
        team, s);
  }
  return s;
}

}  // namespace

Statistics compute_statistics(ConstSpan<double> values, const std::vector<double>& weights,
                              int histogram_bins, int threads) {
  const int team = team_size(threads, block_count(values.size()));
  return statistics_with(values, weights, check_weights(weights, team), histogram_bins, team);
}

std::vector<Statistics> compute_statistics_of_each(const std::vector<ConstSpan<double>>& values,
                                                   const std::vector<double>& weights,
                                                   int histogram_bins, int threads) {
  std::vector<Statistics> out;
  if (values.empty()) return out;
  const int team = team_size(threads, block_count(values[0].size()));
  const WeightCheck c = check_weights(weights, team);
  for (const ConstSpan<double>& v : values) {
    assert(v.size() == values[0].size());
    out.push_back(statistics_with(v, weights, c, histogram_bins, team));
  }
  return out;
}

std::vector<Statistics> compute_statistics_of_each(const std::vector<ConstSpan<double>>& values,
                                                   double equal_weight, int histogram_bins,
                                                   int threads) {
  assert(equal_weight >= 0.0);
  std::vector<Statistics> out;
  if (values.empty()) return out;
  const int team = team_size(threads, block_count(values[0].size()));
  const WeightCheck c = equal_weights(equal_weight, values[0].size());
  for (const ConstSpan<double>& v : values) {
    assert(v.size() == values[0].size());
    out.push_back(statistics_with(v, {}, c, histogram_bins, team));
  }
  return out;
}

}  // namespace meshdev
