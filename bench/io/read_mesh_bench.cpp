// Reader speed on real files from ../shared/data (the readers' unit tests check what is read,
// this checks how fast). Each benchmark is skipped with a message when the data is absent.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "metric/io/mesh_io.h"

namespace meshdev {
namespace {

void BM_ReadMesh(benchmark::State& state, const std::string& relative) {
  const std::filesystem::path path = std::filesystem::path(MESHDEV_SHARED_DATA_DIR) / relative;
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("not present (needs ../shared/data): " + path.string()).c_str());
    return;
  }
  std::size_t faces = 0;
  for (auto _ : state) {
    const TriMesh m = read_mesh(path.string());
    faces = m.num_faces();
    benchmark::DoNotOptimize(faces);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * faces));
  state.counters["faces"] = static_cast<double>(faces);
  state.SetBytesProcessed(
      static_cast<std::int64_t>(state.iterations() * std::filesystem::file_size(path)));
}
BENCHMARK_CAPTURE(BM_ReadMesh, buildings_obj, std::string("large/buildings.obj"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadMesh, bun_zipper_ply, std::string("scalar/stanford_bunny/bun_zipper.ply"))
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace meshdev

BENCHMARK_MAIN();
