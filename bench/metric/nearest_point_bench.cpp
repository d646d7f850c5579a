// Nearest-point index and whole-direction deviation throughput.
//   cmake -DMESHDEV_BUILD_BENCH=ON ... && build/bench/metric_bench
// Meshes: icospheres (level L has 20·4^L faces); samples: scan conversion of a translated,
// coarser or finer icosphere, in generation order (face by face, as compare does).
#include <benchmark/benchmark.h>

#include <algorithm>

#include "metric/attribute_deviation.h"
#include "metric/attributes.h"
#include "metric/nearest_point.h"
#include "metric/sampling.h"
#include "metric/triangle_bvh.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

const TriMesh& sphere(int level) {
  static TriMesh cache[9];
  if (cache[level].faces.empty()) cache[level] = test::icosphere(level);
  return cache[level];
}

SampleSet samples_on(int level, std::size_t count) {
  SamplingOptions o;
  o.vertices = false;
  o.target_count = count;
  return sample_surface(test::translated(sphere(level), {0.003, 0.002, 0.001}), o, 2.0);
}

// BVH build time by target size (level 5: 20k faces, 6: 82k, 7: 328k, 8: 1.3M).
void BM_BvhBuild(benchmark::State& state) {
  const TriMesh& target = sphere(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    TriangleBvh bvh(target);
    benchmark::DoNotOptimize(bvh.node_count());
  }
  state.counters["faces"] = static_cast<double>(target.num_faces());
  state.counters["bytes_per_face"] = static_cast<double>(TriangleBvh(target).memory_bytes()) /
                                     static_cast<double>(target.num_faces());
}
BENCHMARK(BM_BvhBuild)->Arg(5)->Arg(6)->Arg(7)->Unit(benchmark::kMillisecond);

// One exact test (FaceEvaluator::evaluate, the closest point on one face with its barycentrics
// and feature) per iteration, for a point just above each face's centroid of a level-5 icosphere
// in turn (the face region, where nearly every query's answer lies), no source hint. Under
// callgrind, `--benchmark_filter=BM_ExactTest --benchmark_min_time=0.2` gives the instructions per
// test.
void BM_ExactTest(benchmark::State& state) {
  const TriMesh& target = sphere(5);
  const detail::FaceEvaluator eval(target, TieOptions{}, /*with_spheres=*/false, 1);
  std::vector<Vec3> points;
  for (const Triangle& t : target.faces) {
    const Vec3 centroid =
        (1.0 / 3.0) * (target.positions[t[0]] + target.positions[t[1]] + target.positions[t[2]]);
    points.push_back(1.001 * centroid);  // the icosphere is centred on the origin
  }
  const QueryHint hint;
  std::uint32_t face = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(eval.evaluate(points[face], face, hint));
    face = face + 1 == points.size() ? 0 : face + 1;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_ExactTest);

// Single queries in sample order with the previous-hit hint, one thread.
void BM_NearestQuery(benchmark::State& state) {
  const TriMesh& target = sphere(static_cast<int>(state.range(0)));
  TriangleBvh bvh(target);
  const SampleSet s = samples_on(static_cast<int>(state.range(1)), 200000);
  std::vector<SurfaceHit> ties;
  std::size_t i = 0;
  std::uint32_t previous = kNoFace;
  for (auto _ : state) {
    QueryHint hint;
    hint.start_face = previous;
    benchmark::DoNotOptimize(bvh.find(s.samples[i].point, hint, ties));
    previous = ties.front().face;
    i = (i + 1) % s.samples.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_NearestQuery)->Args({5, 7})->Args({7, 5})->Args({7, 7});

// The same queries in batches of 1024 (find_batch: coherent runs answered in packets), one
// thread; counters packet_share = fraction of queries answered in packets, block_share = in
// block packets (where samples are sparse on the target).
void BM_NearestBatch(benchmark::State& state) {
  const TriMesh& target = sphere(static_cast<int>(state.range(0)));
  TriangleBvh bvh(target);
  const SampleSet s = samples_on(static_cast<int>(state.range(1)), 200000);
  std::vector<Vec3> points;
  for (const Sample& x : s.samples) points.push_back(x.point);
  constexpr std::size_t kBatch = 1024;
  BatchHits batch;
  std::size_t i = 0, queries = 0, in_packets = 0, in_blocks = 0;
  for (auto _ : state) {
    const std::size_t count = std::min(kBatch, points.size() - i);
    const std::size_t answered = bvh.find_batch(points.data() + i, nullptr, count, batch);
    benchmark::DoNotOptimize(batch.distance.data());
    queries += answered;
    in_packets += batch.packet_queries;
    in_blocks += batch.block_packet_queries;
    i = (i + answered) % points.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(queries));
  state.counters["packet_share"] = static_cast<double>(in_packets) / static_cast<double>(queries);
  state.counters["block_share"] = static_cast<double>(in_blocks) / static_cast<double>(queries);
}
BENCHMARK(BM_NearestBatch)->Args({5, 7})->Args({7, 5})->Args({7, 7});

// The whole per-sample loop (closest point, ties, geometry + normal measures) on 1M samples,
// by thread count.
void BM_Deviations(benchmark::State& state) {
  const TriMesh& a = sphere(7);
  const TriMesh& b = sphere(5);
  const SampleSet s = samples_on(7, 1000000);
  AttributePlan plan = plan_attributes(a, b, {}, "A", "B");
  TriangleBvh bvh(b);
  for (auto _ : state) {
    DeviationOptions options;  // what `meshdev compare` asks for
    options.threads = static_cast<int>(state.range(0));
    options.keep_nearest = false;
    SampleDeviations d = compute_deviations(s, plan.a, plan.b, bvh, plan.measures, options);
    benchmark::DoNotOptimize(d.values[0].data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * s.samples.size()));
}
BENCHMARK(BM_Deviations)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace meshdev

BENCHMARK_MAIN();
