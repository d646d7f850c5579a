#pragma once
// The arithmetic kernel of the host probes (bench/peers/host_probe.cpp and peer_compare's probe
// before each meshdev run of its rounds), so that both time the same code.

namespace meshdev_bench {

// `iterations` steps of K independent chains of dependent double multiply-adds, in registers (no
// memory); their sum, which the caller keeps so that nothing is dropped. K = 4 leaves the
// floating-point pipes mostly idle (latency-bound); K = 16 fills them (throughput-bound): two
// vCPUs on one physical core's two hardware threads then share the pipes, and the second thread
// gains about 1.4x instead of 2x (docs/performance.md §1, "The host's state").
template <int K>
double fp_chains(long iterations) {
  double v[K];
  for (int k = 0; k < K; ++k) v[k] = 1.0 + 0.01 * k;
  for (long i = 0; i < iterations; ++i)
#pragma GCC unroll 16
    for (int k = 0; k < K; ++k) v[k] = v[k] * 0.9999999 + 1e-9;
  double sum = 0.0;
  for (int k = 0; k < K; ++k) sum += v[k];
  return sum;
}

}  // namespace meshdev_bench
