// Whole comparisons (compare_meshes) as a sweep runs them: one mesh against several of its
// "simplifications", fresh each time or through one ComparisonReference of the mesh.
//   cmake -DMESHDEV_BUILD_BENCH=ON ... && build/bench/compare_bench
// Meshes: a level-6 icosphere stored in a random order (81,920 faces, as files stored in no
// spatial order give them) against coarser icospheres moved slightly off it (levels 5 to 2:
// 75 % to 99.6 % of the faces removed), default options (geometry and normals, vertices and scan
// conversion, 10 x the larger face count per direction).
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "metric/compare.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

struct SweepMeshes {
  TriMesh mesh = test::shuffled(test::icosphere(6), 1);
  std::vector<TriMesh> simplified;
  SweepMeshes() {
    for (int level = 5; level >= 2; --level)
      simplified.push_back(test::translated(test::icosphere(level), {0.003, 0.002, 0.001}));
  }
};

const SweepMeshes& sweep_meshes() {
  static const SweepMeshes m;
  return m;
}

// One iteration compares the mesh with each of the four coarser ones: fresh (range(0) = 0) or
// through one ComparisonReference made in the iteration (1), on range(1) threads.
void BM_SweepComparisons(benchmark::State& state) {
  const bool reference = state.range(0) != 0;
  const SweepMeshes& m = sweep_meshes();
  CompareOptions o;
  o.threads = static_cast<int>(state.range(1));
  for (auto _ : state) {
    double sum = 0;
    if (reference) {
      ComparisonReference a(m.mesh, "A", o.threads);
      for (const TriMesh& b : m.simplified) sum += compare_meshes(a, b, o).symmetric[0].mean;
    } else {
      for (const TriMesh& b : m.simplified) sum += compare_meshes(m.mesh, b, o).symmetric[0].mean;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * m.simplified.size()));
  state.SetLabel(std::string(reference ? "one reference" : "fresh") + ", " +
                 std::to_string(o.threads) + (o.threads == 1 ? " thread" : " threads"));
}
BENCHMARK(BM_SweepComparisons)
    ->ArgsProduct({{0, 1}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace meshdev

BENCHMARK_MAIN();
