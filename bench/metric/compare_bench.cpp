// Whole comparisons (compare_meshes) as a sweep runs them: one mesh against several of its
// "simplifications", fresh each time or through one ComparisonReference of the mesh.
//   cmake -DMESHDEV_BUILD_BENCH=ON ... && build/bench/compare_bench
//   build/bench/compare_bench --reference A.off --compared B1.ply,B2.ply,... [benchmark flags]
// Built in: a level-6 icosphere stored in a random order (81,920 faces, as files stored in no
// spatial order give them) against coarser icospheres moved slightly off it (levels 5 to 2: 75 %
// to 99.6 % of the faces removed). With --reference and --compared (before Google Benchmark's own
// flags), also the mesh A read from a file against each of the files B (e.g. `meshdev simplify`
// outputs), on 2 threads. Default options: geometry and normals, vertices and scan conversion,
// 10 x the larger face count per direction. `--benchmark_enable_random_interleaving=true` with
// repetitions alternates the fresh and the reference runs.
#include <benchmark/benchmark.h>

#include <exception>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "metric/compare.h"
#include "metric/io/mesh_io.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

struct SweepMeshes {
  TriMesh mesh;
  std::vector<TriMesh> simplified;
};

const SweepMeshes& built_in_meshes() {
  static const SweepMeshes m = [] {
    SweepMeshes s{test::shuffled(test::icosphere(6), 1), {}};
    for (int level = 5; level >= 2; --level)
      s.simplified.push_back(test::translated(test::icosphere(level), {0.003, 0.002, 0.001}));
    return s;
  }();
  return m;
}

// One iteration compares m.mesh with each of m.simplified: fresh (reference false) or through
// one ComparisonReference made in the iteration, on `threads` threads.
void compare_each(benchmark::State& state, const SweepMeshes& m, bool reference, int threads) {
  CompareOptions o;
  o.threads = threads;
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
                 std::to_string(m.simplified.size()) + " meshes, " + std::to_string(threads) +
                 (threads == 1 ? " thread" : " threads"));
}

// range(0): 0 fresh, 1 one reference; range(1): threads.
void BM_SweepComparisons(benchmark::State& state) {
  compare_each(state, built_in_meshes(), state.range(0) != 0, static_cast<int>(state.range(1)));
}
BENCHMARK(BM_SweepComparisons)
    ->ArgsProduct({{0, 1}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace meshdev

int main(int argc, char** argv) {
  std::string reference, compared;
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--reference" || arg == "--compared") && i + 1 < argc)
      (arg == "--reference" ? reference : compared) = argv[++i];
    else
      rest.push_back(argv[i]);
  }
  if (reference.empty() != compared.empty()) {
    std::cerr << "compare_bench: --reference and --compared go together\n";
    return 2;
  }
  static meshdev::SweepMeshes files;
  if (!reference.empty()) {
    try {
      files.mesh = meshdev::read_mesh(reference);
      std::istringstream list(compared);
      for (std::string path; std::getline(list, path, ',');)
        if (!path.empty()) files.simplified.push_back(meshdev::read_mesh(path));
    } catch (const std::exception& e) {
      std::cerr << "compare_bench: " << e.what() << '\n';
      return 3;
    }
    for (const bool with_reference : {false, true})
      benchmark::RegisterBenchmark(
          with_reference ? "BM_FileComparisons/reference" : "BM_FileComparisons/fresh",
          [with_reference](benchmark::State& state) {
            meshdev::compare_each(state, files, with_reference, 2);
          })
          ->UseRealTime()
          ->Unit(benchmark::kMillisecond);
  }
  int count = static_cast<int>(rest.size());
  benchmark::Initialize(&count, rest.data());
  if (benchmark::ReportUnrecognizedArguments(count, rest.data())) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
