// Statistics of one measure over a direction's samples (min, max, mean, RMS, variance,
// quantiles, histogram): compute_statistics runs once per measure and direction.
//   cmake -DMESHDEV_BUILD_BENCH=ON ... && build/bench/statistics_bench
// Values: a deviation-like long tail (|N(0, 1)| e^N(0, 1)) shared by runs of 256 samples, times
// 1 + 0.1 N(0, 1) per sample: neighbouring samples deviate alike, as they do in sample order.
// Weights all equal (Monte Carlo samples) or spread (scan-converted samples weigh their share of
// the face's area). Third argument: the percentage of exact zeros (coplanar parts: 76-99 % of
// the samples of buildings.ply against its 40k-face simplification). Fourth: the threads.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "metric/statistics.h"

namespace meshdev {
namespace {

void BM_Statistics(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const bool spread = state.range(1) != 0;
  const double zeros = static_cast<double>(state.range(2)) / 100.0;
  const int threads = static_cast<int>(state.range(3));
  std::mt19937_64 rng(1);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> uniform(0.5, 1.5);
  std::vector<double> values(n), weights(n);
  double run = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (i % 256 == 0) run = std::fabs(gauss(rng)) * std::exp(gauss(rng));
    const bool zero = zeros > 0.0 && uniform(rng) - 0.5 < zeros;  // (no draw at 0 %)
    values[i] = zero ? 0.0 : std::fabs(run * (1.0 + 0.1 * gauss(rng)));
    weights[i] = spread ? uniform(rng) : 1e-6;
  }
  for (auto _ : state) {
    const Statistics s = compute_statistics(values, weights, 20, threads);
    benchmark::DoNotOptimize(s.p99);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
  state.SetLabel(std::string(spread ? "spread weights" : "equal weights") + ", " +
                 std::to_string(state.range(2)) + " % zeros, " + std::to_string(threads) +
                 (threads == 1 ? " thread" : " threads"));
}
BENCHMARK(BM_Statistics)
    ->ArgsProduct({{1 << 20}, {0, 1}, {0, 75}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace meshdev

BENCHMARK_MAIN();
