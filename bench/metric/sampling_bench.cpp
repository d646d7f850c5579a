// The samplers' visit orders, and what the order of the samples does to a direction's queries.
//   cmake -DMESHDEV_BUILD_BENCH=ON ... && build/bench/sampling_bench
// Meshes: icospheres (level L has 20·4^L faces) with their vertices and faces stored in a random
// order (test::shuffled), as files stored in no spatial order give them (buildings.ply, the
// Stanford armadillo).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>

#include "metric/attribute_deviation.h"
#include "metric/attributes.h"
#include "metric/nearest_point.h"
#include "metric/sampling.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

const TriMesh& shuffled_sphere(int level) {
  static TriMesh cache[9];
  if (cache[level].faces.empty()) cache[level] = test::shuffled(test::icosphere(level), 1);
  return cache[level];
}

// detail::face_visit_order (the Morton order of the faces' centroids, codes and radix sort on the
// team) by mesh size and threads: what every sampler pays before its first sample.
void BM_FaceVisitOrder(benchmark::State& state) {
  const TriMesh& mesh = shuffled_sphere(static_cast<int>(state.range(0)));
  const int threads = static_cast<int>(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(detail::face_visit_order(mesh, threads).data());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * mesh.num_faces()));
  state.SetLabel(std::to_string(mesh.num_faces()) + " faces, " + std::to_string(threads) +
                 (threads == 1 ? " thread" : " threads"));
}
BENCHMARK(BM_FaceVisitOrder)
    ->ArgsProduct({{4, 5, 6, 8}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// compute_deviations (geometry, normal, normal angle) of the default samples (vertices and scan
// conversion, 10 per face) of a shuffled level-6 icosphere (81,920 faces) against a level-4 one
// moved off it (5,120 faces: 16 samples per face, dense, as buildings.ply against its 40k-face
// simplification), in the samplers' order (vertices, then faces, each along a Morton curve) and
// in index order (vertices, then faces, by index: the samplers' order before the twenty-fourth
// session; docs/performance-log.md §3). The same samples and results either way.
void BM_DefaultSamplesQueried(benchmark::State& state) {
  const bool curve = state.range(0) != 0;
  const int threads = static_cast<int>(state.range(1));
  const TriMesh& a = shuffled_sphere(6);
  static const TriMesh b = test::translated(test::icosphere(4), {0.003, 0.002, 0.001});
  AttributeOptions attributes;
  attributes.threads = threads;
  const AttributePlan plan = plan_attributes(a, b, attributes, "A", "B");
  SamplingOptions o;
  o.target_count = 10 * a.num_faces();
  o.threads = threads;
  SampleSet set = sample_surface(a, o, 2.0);
  if (!curve)
    std::stable_sort(set.samples.begin(), set.samples.end(), [](const Sample& x, const Sample& y) {
      if (x.kind != y.kind) return x.kind < y.kind;
      return x.kind == SampleKind::kVertex ? x.vertex < y.vertex : x.face < y.face;
    });
  const auto index = make_nearest_point_index(b, IndexKind::kBvh, {}, threads);
  DeviationOptions d;
  d.threads = threads;
  for (auto _ : state) {
    const SampleDeviations dev = compute_deviations(set, plan.a, plan.b, *index, plan.measures, d);
    benchmark::DoNotOptimize(dev.values[0].data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * set.samples.size()));
  state.SetLabel(std::string(curve ? "curve order" : "index order") + ", " +
                 std::to_string(set.samples.size()) + " samples, " + std::to_string(threads) +
                 (threads == 1 ? " thread" : " threads"));
}
BENCHMARK(BM_DefaultSamplesQueried)
    ->ArgsProduct({{0, 1}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace meshdev

BENCHMARK_MAIN();
