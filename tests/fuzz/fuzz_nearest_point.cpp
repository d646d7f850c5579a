// libFuzzer target: bytes -> a small valid-but-weird mesh (degenerate, duplicate, non-manifold
// triangles, extreme coordinates) and query points -> the BVH, the grid and the brute-force
// oracle, one query at a time and as a batch (find_batch). They must return bit-identical
// distances and tie sets, and nothing may be NaN. The mesh's samples made on demand
// (SampleSequence) must be the stored ones (sample_surface), bit for bit, or both refused.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "metric/errors.h"
#include "metric/nearest_point.h"
#include "metric/sampling.h"
#include "tests/fuzz/fuzz_input.h"

namespace {

using meshdev::SurfaceHit;

void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "fuzz_nearest_point: %s\n", what);
    std::abort();
  }
}

void check_hits(const std::vector<SurfaceHit>& hits, double distance) {
  require(std::isfinite(distance) && distance >= 0, "distance not finite or negative");
  require(!hits.empty(), "no nearest face");
  for (const SurfaceHit& h : hits) {
    require(std::isfinite(h.sq_distance) && h.sq_distance >= 0, "squared distance not finite");
    require(std::isfinite(h.point.x) && std::isfinite(h.point.y) && std::isfinite(h.point.z),
            "nearest point not finite");
    for (double b : h.bary) require(std::isfinite(b), "barycentric not finite");
  }
}

bool same_sample(const meshdev::Sample& x, const meshdev::Sample& y) {
  return x.point == y.point && x.face == y.face && x.vertex == y.vertex && x.bary == y.bary &&
         x.weight == y.weight && x.kind == y.kind;
}

// SampleSequence against sample_surface for the mesh's default and Monte Carlo sampling, alone
// and with vertices; a small target count, so that the step search stays short.
void check_samples(const meshdev::TriMesh& mesh, std::uint8_t seed) {
  for (const char* kinds : {"vertices,faces", "faces", "montecarlo", "vertices,montecarlo"}) {
    meshdev::SamplingOptions o;
    meshdev::set_sample_kinds(o, kinds);
    o.target_count = 16 + seed % 200;
    o.seed = seed;
    o.threads = 1;
    const double diagonal = meshdev::bounding_box(mesh).diagonal();
    meshdev::SampleSet set;
    bool stored_refused = false, made_refused = false;
    try {
      set = meshdev::sample_surface(mesh, o, diagonal);
    } catch (const meshdev::InvalidInput&) {
      stored_refused = true;
    }
    std::unique_ptr<meshdev::SampleSequence> made;
    try {
      made = std::make_unique<meshdev::SampleSequence>(mesh, o, diagonal);
    } catch (const meshdev::InvalidInput&) {
      made_refused = true;
    }
    require(stored_refused == made_refused,
            "SampleSequence and sample_surface disagree on refusing");
    if (stored_refused) continue;
    require(made->size() == set.samples.size(), "SampleSequence makes a different sample count");
    require(made->equal_weight() == set.equal_weight && made->step() == set.step,
            "SampleSequence and sample_surface disagree on the weight or the step");
    std::vector<meshdev::Sample> all(made->size());
    made->generate_all(all.data(), 1);
    std::vector<double> weights(made->size());
    made->weights(weights.data(), 1);
    for (std::size_t i = 0; i < all.size(); ++i) {
      require(same_sample(all[i], set.samples[i]), "SampleSequence makes a different sample");
      require(weights[i] == set.samples[i].weight, "SampleSequence gives a different weight");
    }
  }
}

bool same(const std::vector<SurfaceHit>& x, const std::vector<SurfaceHit>& y) {
  if (x.size() != y.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i].face != y[i].face || x[i].sq_distance != y[i].sq_distance || x[i].bary != y[i].bary ||
        x[i].feature != y[i].feature)
      return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  meshdev::fuzz::ByteReader in(data, size);
  const meshdev::TriMesh mesh = meshdev::fuzz::small_mesh(in);
  const auto bvh = meshdev::make_nearest_point_index(mesh, meshdev::IndexKind::kBvh);
  const auto grid = meshdev::make_nearest_point_index(mesh, meshdev::IndexKind::kGrid);
  const auto brute = meshdev::make_nearest_point_index(mesh, meshdev::IndexKind::kBruteForce);
  std::vector<SurfaceHit> hb, hg, hf;
  // Queries: every vertex (ties at shared corners), then points from the remaining bytes, some
  // with a source-triangle hint (the exact-zero rule) or a start face.
  std::vector<meshdev::Vec3> queries = mesh.positions;
  while (!in.empty() && queries.size() < 64) queries.push_back(meshdev::fuzz::point(in));
  for (std::size_t q = 0; q < queries.size(); ++q) {
    meshdev::QueryHint hint;
    const meshdev::Triangle& t = mesh.faces[q % mesh.num_faces()];
    const meshdev::Vec3 corners[3] = {mesh.positions[t[0]], mesh.positions[t[1]],
                                      mesh.positions[t[2]]};
    if (q % 3 == 1) {
      hint.source = corners;
      hint.source_bary = {1, 0, 0};
      queries[q] = corners[0];
    }
    if (q % 3 == 2) hint.start_face = static_cast<std::uint32_t>(q % mesh.num_faces());
    const double db = bvh->find(queries[q], hint, hb);
    const double dg = grid->find(queries[q], hint, hg);
    const double df = brute->find(queries[q], hint, hf);
    check_hits(hf, df);
    require(db == df && dg == df, "BVH, grid and brute force disagree on the distance");
    require(same(hb, hf), "BVH and brute force disagree on the ties");
    require(same(hg, hf), "grid and brute force disagree on the ties");
  }

  // The same queries as one batch, each followed by 9 near copies (steps of 1e-4 of the mesh's
  // bounding box), so that the BVH answers runs of them in packets (find_batch): every answer
  // must still be the oracle's.
  const double step = 1e-4 * meshdev::bounding_box(mesh).diagonal();
  std::vector<meshdev::Vec3> points, corners;
  std::vector<meshdev::QueryHint> hints;
  for (std::size_t q = 0; q < queries.size(); ++q)
    for (int j = 0; j < 10; ++j) {
      points.push_back(queries[q] + (j * step) * meshdev::Vec3{1.0, -1.0, 0.5});
      const meshdev::Triangle& t = mesh.faces[q % mesh.num_faces()];
      for (int c = 0; c < 3; ++c) corners.push_back(mesh.positions[t[c]]);
      hints.emplace_back();
    }
  for (std::size_t i = 0; i < points.size(); ++i)
    if ((i / 10) % 3 == 1) {  // corners no longer move
      hints[i].source = &corners[3 * i];
      hints[i].source_bary = {1, 0, 0};
    }
  meshdev::BatchHits batch;
  bvh->find_batch(points.data(), hints.data(), points.size(), batch);
  require(batch.size() == points.size(), "find_batch answered a different number of queries");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double df = brute->find(points[i], hints[i], hf);
    hb.assign(batch.ties_begin(i), batch.ties_begin(i) + batch.tie_count(i));
    require(batch.distance[i] == df, "BVH batch and brute force disagree on the distance");
    require(same(hb, hf), "BVH batch and brute force disagree on the ties");
  }
  check_samples(mesh, size > 0 ? data[0] : 0);
  return 0;
}
