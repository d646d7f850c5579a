// Reader speed on real files from ../shared/data (the readers' unit tests check what is read,
// this checks how fast), on 1 and 2 threads (the argument: large OBJ and OFF files are parsed in
// chunks on the team). Each benchmark is skipped with a message when the data is absent.
// BM_ReadBinaryPly reads a binary PLY written here from a 1.3 M-face icosphere (float or double
// x y z, uchar count + int indices: what write_ply, MeshLab and most scanners write), so it runs
// everywhere.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "metric/io/mesh_io.h"
#include "metric/io/write_ply.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

void BM_ReadMesh(benchmark::State& state, const std::string& relative) {
  const std::filesystem::path path = std::filesystem::path(MESHDEV_SHARED_DATA_DIR) / relative;
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("not present (needs ../shared/data): " + path.string()).c_str());
    return;
  }
  const auto threads = static_cast<int>(state.range(0));
  std::size_t faces = 0;
  for (auto _ : state) {
    const TriMesh m = read_mesh(path.string(), threads);
    faces = m.num_faces();
    benchmark::DoNotOptimize(faces);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * faces));
  state.counters["faces"] = static_cast<double>(faces);
  state.SetBytesProcessed(
      static_cast<std::int64_t>(state.iterations() * std::filesystem::file_size(path)));
}
BENCHMARK_CAPTURE(BM_ReadMesh, buildings_obj, std::string("large/buildings.obj"))
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadMesh, koala_obj, std::string("plain/koala.obj"))
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadMesh, armadillo_off, std::string("plain/armadillo.off"))
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadMesh, bun_zipper_ply, std::string("scalar/stanford_bunny/bun_zipper.ply"))
    ->ArgName("threads")
    ->Arg(1)
    ->Unit(benchmark::kMillisecond);

void BM_ReadBinaryPly(benchmark::State& state) {
  const bool double_positions = state.range(0) != 0;
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      (std::string("meshdev_io_bench_") + (double_positions ? "double" : "float") + ".ply");
  PlyWriteOptions options;
  options.double_positions = double_positions;
  const TriMesh sphere = test::icosphere(8);
  write_ply(path.string(), sphere, options);
  for (auto _ : state) {
    const TriMesh m = read_mesh(path.string());
    benchmark::DoNotOptimize(m.faces.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * sphere.num_faces()));
  state.counters["faces"] = static_cast<double>(sphere.num_faces());
  state.SetBytesProcessed(
      static_cast<std::int64_t>(state.iterations() * std::filesystem::file_size(path)));
  state.SetLabel(double_positions ? "double x y z" : "float x y z");
  std::filesystem::remove(path);
}
BENCHMARK(BM_ReadBinaryPly)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace meshdev

BENCHMARK_MAIN();
