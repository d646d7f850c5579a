// host_probe: what the machine gives right now, on 1 and 2 threads, as a control beside
// peer_compare's throughputs. A shared host moves meshdev's 0.1-0.2 s runs by 20-30 % from one
// second to the next; this says whether it moved the host's own arithmetic, memory latency and
// memory bandwidth at the same time (docs/performance.md §1).
//
// usage: host_probe [--rounds R] [--mib M] [--csv FILE]
//
// Four kernels, each timed on 1 and 2 threads in every round (the order of the thread counts
// reversed every other round, as peer_compare --rounds does), the same total work on both:
//   chains    - four independent chains of dependent double multiply-adds per thread, in
//               registers: no memory, and the floating-point pipes mostly idle (latency-bound).
//   pipes     - sixteen such chains: the pipes full (throughput-bound, as meshdev's kernels
//               are). Two vCPUs that the host runs on the two hardware threads of one physical
//               core share its pipes: this kernel then gains about 1.4x from the second thread
//               where `chains` still gains 2x (seen here in the forty-seventh session).
//               Both reported as the 2-thread speed-up (ideal 2).
//   latency   - a dependent random walk through a cycle over M MiB (default 256) of 32-bit
//               indices, one walk per thread: ns per load (the cache misses a query waits for).
//   bandwidth - the triad c = a + 1.5 b over three arrays of M/2 MiB each: GB/s read and written.
// Per kernel: the median and range over the rounds, and for the two compute kernels the median
// of the rounds' own 2-over-1-thread ratios. With --csv, one row per (round, kernel, thread count)
// is appended to FILE. The walk's cycle and the arrays are made before the rounds, from a fixed
// seed. About 1.5 + 0.9 R seconds.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "bench/peers/fp_chains.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// One random cycle through all n slots (Sattolo's algorithm), so a walk never short-circuits.
std::vector<std::uint32_t> random_cycle(std::size_t n, std::uint64_t seed) {
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::mt19937_64 rng(seed);
  for (std::size_t i = n - 1; i > 0; --i) {
    std::uniform_int_distribution<std::size_t> pick(0, i - 1);
    std::swap(order[i], order[pick(rng)]);
  }
  std::vector<std::uint32_t> next(n);
  for (std::size_t i = 0; i < n; ++i) next[order[i]] = order[(i + 1) % n];
  return next;
}

struct Series {
  const char* kernel;
  const char* unit;
  std::vector<double> value[2];  // [1 thread, 2 threads] per round
};

}  // namespace

int main(int argc, char** argv) {
  int rounds = 5;
  std::size_t mib = 256;
  std::string csv;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    if (s == "--rounds" && i + 1 < argc) {
      rounds = std::max(1, std::stoi(argv[++i]));
    } else if (s == "--mib" && i + 1 < argc) {
      mib = static_cast<std::size_t>(std::max(16, std::stoi(argv[++i])));
    } else if (s == "--csv" && i + 1 < argc) {
      csv = argv[++i];
    } else {
      std::fprintf(stderr, "usage: host_probe [--rounds R] [--mib M] [--csv FILE]\n");
      return 2;
    }
  }
  const std::size_t slots = mib * (std::size_t{1} << 20) / sizeof(std::uint32_t);
  const std::vector<std::uint32_t> next = random_cycle(slots, 20261206);
  const std::size_t n = mib * (std::size_t{1} << 20) / 2 / sizeof(double) / 3 * 3;
  std::vector<double> a(n, 1.0), b(n, 2.0), c(n, 0.0);

  constexpr long kChainSteps = 60'000'000;  // about 0.1 s on one thread here (4 chains)
  constexpr long kPipeSteps = 60'000'000;   // about 0.2 s (16 chains)
  constexpr long kWalkSteps = 1'000'000;    // per thread: about 0.1 s at 100 ns a load
  Series compute{"chains", "s", {}}, pipes{"pipes", "s", {}}, latency{"latency", "ns/load", {}},
      bandwidth{"triad", "GB/s", {}};
  double sink = 0.0;
  std::uint64_t walked = 0;
  std::string rows;
  for (int r = 0; r < rounds; ++r) {
    for (int step = 0; step < 2; ++step) {
      const int t = r % 2 == 0 ? step : 1 - step;
      const int threads = t + 1;
      Clock::time_point t0 = Clock::now();
      double sum = 0.0;
#pragma omp parallel num_threads(threads) reduction(+ : sum)
      sum += meshdev_bench::fp_chains<4>(kChainSteps / threads);
      compute.value[t].push_back(seconds_since(t0));
      sink += sum;

      t0 = Clock::now();
      sum = 0.0;
#pragma omp parallel num_threads(threads) reduction(+ : sum)
      sum += meshdev_bench::fp_chains<16>(kPipeSteps / threads);
      pipes.value[t].push_back(seconds_since(t0));
      sink += sum;

      t0 = Clock::now();
      std::uint64_t acc = 0;
#pragma omp parallel num_threads(threads) reduction(+ : acc)
      {
        std::uint32_t j = static_cast<std::uint32_t>(omp_get_thread_num()) * 7919u;
        for (long k = 0; k < kWalkSteps; ++k) j = next[j];
        acc += j;
      }
      latency.value[t].push_back(seconds_since(t0) / kWalkSteps * 1e9);
      walked += acc;

      t0 = Clock::now();
#pragma omp parallel for num_threads(threads) schedule(static)
      for (std::size_t i = 0; i < n; ++i) c[i] = a[i] + 1.5 * b[i];
      bandwidth.value[t].push_back(3.0 * static_cast<double>(n) * sizeof(double) /
                                   seconds_since(t0) / 1e9);
      sink += c[r];

      for (const Series* s : {&compute, &pipes, &latency, &bandwidth}) {
        char line[160];
        std::snprintf(line, sizeof line, "%d,%s,%d,%.6g,%s\n", r + 1, s->kernel, threads,
                      s->value[t].back(), s->unit);
        rows += line;
      }
    }
  }

  auto span = [](const std::vector<double>& v) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    char text[96];
    std::snprintf(text, sizeof text, "%.3g (%.3g-%.3g)", median_of(v), *lo, *hi);
    return std::string(text);
  };
  auto speedup = [&](const Series& s) {
    std::vector<double> ratio;
    for (int r = 0; r < rounds; ++r) ratio.push_back(s.value[0][r] / s.value[1][r]);
    return span(ratio);
  };
  std::printf("host_probe, %d rounds (medians, ranges in brackets):\n", rounds);
  std::printf(
      "  2-thread speed-up (ideal 2): 4 chains (latency-bound) %s, 16 chains "
      "(throughput-bound) %s\n",
      speedup(compute).c_str(), speedup(pipes).c_str());
  std::printf("  memory latency %s ns a load on 1 thread, %s on 2 (%zu MiB walk)\n",
              span(latency.value[0]).c_str(), span(latency.value[1]).c_str(), mib);
  std::printf("  triad bandwidth %s GB/s on 1 thread, %s on 2\n", span(bandwidth.value[0]).c_str(),
              span(bandwidth.value[1]).c_str());
  if (sink == 0.0 && walked == 42) std::printf("(never)\n");  // keeps the work
  if (!csv.empty()) {
    std::ifstream probe(csv);
    const bool fresh = !probe.good() || probe.peek() == std::ifstream::traits_type::eof();
    probe.close();
    std::ofstream f(csv, std::ios::app);
    if (fresh) f << "round,kernel,threads,value,unit\n";
    f << rows;
    if (!f) {
      std::fprintf(stderr, "host_probe: cannot write %s\n", csv.c_str());
      return 1;
    }
  }
  return 0;
}
