# Google Benchmark 1.7 (Debian: libbenchmark-dev). Provides benchmark::benchmark.
find_package(benchmark REQUIRED)
