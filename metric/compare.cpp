#include "metric/compare.h"

#include <omp.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <optional>

#include "metric/errors.h"

namespace meshdev {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

DirectionResult run_direction(const PreparedMesh& from, const PreparedMesh& to,
                              const std::vector<Measure>& measures, const CompareOptions& o,
                              const SamplingOptions& sampling, double diagonal,
                              const std::string& from_label, const std::string& to_label,
                              std::optional<SampleSequence>* samples_store,
                              std::unique_ptr<NearestPointIndex>* index_store) {
  DirectionResult r;
  r.from = from_label;
  r.to = to_label;
  if (to.mesh->faces.empty())
    throw InvalidInput(to_label + " has no faces: the distance to its surface is undefined" +
                       std::string(o.direction == Direction::kBoth
                                       ? " (use --direction forward to sample it only)"
                                       : ""));

  // Samples without edge samples (the default vertices and scan conversion, Monte Carlo), where
  // no per-sample output is kept, are made a chunk at a time as they are queried instead of
  // stored (72 bytes each): the same samples and results.
  auto t0 = Clock::now();
  std::optional<SampleSequence> local_sequence;
  const SampleSequence* generated = nullptr;
  SampleSet samples;
  double equal_weight = 0.0;
  if (!o.keep_samples && sequence_sampling(sampling)) {
    std::optional<SampleSequence>& store = samples_store ? *samples_store : local_sequence;
    r.samples_reused = store.has_value();
    if (!store) store.emplace(*from.mesh, sampling, diagonal);
    generated = &*store;
    r.sampling = generated->description();
    r.step = generated->step();
    r.samples = generated->size();
    equal_weight = generated->equal_weight();
  } else {
    samples = sample_surface(*from.mesh, sampling, diagonal);
    r.sampling = samples.description;
    r.step = samples.step;
    r.samples = samples.samples.size();
    equal_weight = samples.equal_weight;
  }
  if (r.samples == 0)
    throw InvalidInput(from_label + " gave no samples (no referenced vertices and no faces)");
  r.seconds_sampling = seconds_since(t0);
  auto sample = [&](std::size_t i) { return generated ? generated->at(i) : samples.samples[i]; };

  // The direction's per-sample memory (the deviations, and the weights where they differ) is
  // checked before the index is built: a count that cannot fit is refused before any work.
  DeviationOptions deviation_options;
  deviation_options.threads = o.threads;
  deviation_options.keep_nearest = o.keep_samples;
  check_deviations_fit_in_memory(r.samples, measures, deviation_options,
                                 equal_weight > 0.0 ? 0.0 : static_cast<double>(sizeof(double)));

  t0 = Clock::now();
  std::unique_ptr<NearestPointIndex> local_index;
  std::unique_ptr<NearestPointIndex>& index = index_store ? *index_store : local_index;
  r.index_reused = index != nullptr;
  if (!index) index = make_nearest_point_index(*to.mesh, o.index, o.ties, o.threads);
  r.seconds_index = seconds_since(t0);
  r.index = index->name();

  t0 = Clock::now();
  SampleDeviations dev =
      generated ? compute_deviations(*generated, from, to, *index, measures, deviation_options)
                : compute_deviations(samples, from, to, *index, measures, deviation_options);
  r.seconds_query = seconds_since(t0);
  // The nearest point of one sample: kept, or found again (the same query gives the same answer).
  std::vector<SurfaceHit> ties;
  auto nearest_of = [&](std::size_t i) {
    if (!dev.nearest.empty()) return dev.nearest[i];
    const Sample s = sample(i);
    index->find(s.point, sample_hint(*from.mesh, s), ties);
    return ties.front();
  };

  // Each measure on the whole team (its numbers do not depend on the thread count); the weights
  // gathered from the samples only where they differ.
  const std::vector<ConstSpan<double>> values(dev.values.begin(), dev.values.end());
  if (equal_weight > 0.0) {
    r.stats = compute_statistics_of_each(values, equal_weight, o.histogram_bins, o.threads);
  } else {
    std::vector<double> weights(r.samples);
    if (generated) {
      generated->weights(weights.data(), o.threads);
    } else {
      const auto n = static_cast<std::int64_t>(samples.samples.size());
#pragma omp parallel for num_threads(o.threads > 0 ? o.threads : omp_get_max_threads()) \
    schedule(static)
      for (std::int64_t i = 0; i < n; ++i) weights[i] = samples.samples[i].weight;
    }
    r.stats = compute_statistics_of_each(values, weights, o.histogram_bins, o.threads);
  }
  for (std::size_t m = 0; m < measures.size(); ++m) {
    const std::size_t i = r.stats[m].argmax;
    const Sample s = sample(i);
    const SurfaceHit h = nearest_of(i);
    r.max_location.push_back(
        {i, s.point, s.kind, s.face, h.point, h.face, h.feature, dev.values[m][i]});
  }
  const auto count = static_cast<std::int64_t>(dev.nearest_feature.size());
  std::size_t on_vertex = 0, on_edge = 0, on_face = 0, with_ties = 0;
#pragma omp parallel for num_threads(o.threads > 0 ? o.threads : omp_get_max_threads()) \
    schedule(static) reduction(+ : on_vertex, on_edge, on_face, with_ties)
  for (std::int64_t i = 0; i < count; ++i) {
    const Feature f = dev.nearest_feature[i];
    on_vertex += f == Feature::kVertex;
    on_edge += f == Feature::kEdge;
    on_face += f == Feature::kFace;
    with_ties += dev.tie_count[i] > 1;
  }
  r.nearest_feature = {on_vertex, on_edge, on_face};
  r.samples_with_ties = with_ties;
  r.cohen_multiple = dev.cohen_multiple;
  r.cohen_outside = dev.cohen_outside;
  r.cohen_max_uv_gap = dev.cohen_max_uv_gap;
  if (o.keep_samples) {
    r.sample_set = std::move(samples);
    r.deviations = std::move(dev);
  }
  return r;
}

}  // namespace

MeshSummary summarize(const TriMesh& mesh, const std::string& label, int threads) {
  MeshSummary s;
  s.label = label;
  s.vertices = mesh.num_vertices();
  const ReferencedVertices referenced = referenced_vertex_summary(mesh, threads);
  s.referenced_vertices = referenced.count;
  s.faces = mesh.num_faces();
  s.polygons = mesh.source_polygons > 0 ? mesh.source_polygons : mesh.num_faces();
  s.area = surface_area(mesh, threads);
  s.box = referenced.box;
  for (const AttributeChannel& c : mesh.channels) s.channels.push_back(c.name);
  return s;
}

namespace {

// The sampling options of both directions: the default count is 10 x the larger face count.
SamplingOptions resolved_sampling(const CompareOptions& options, const TriMesh& a,
                                  const TriMesh& b) {
  SamplingOptions sampling = options.sampling;
  sampling.threads = options.threads;
  if (sampling.target_count == 0)
    sampling.target_count = 10 * std::max(a.num_faces(), b.num_faces());
  return sampling;
}

// What a comparison keeps of mesh A for the next one (ComparisonReference); null: nothing is
// kept. An empty store is filled; a filled one is used (made for the same mesh and options).
struct ReferenceStores {
  ReferenceAttributes* attributes = nullptr;
  std::optional<SampleSequence>* samples = nullptr;     // A's samples (forward direction)
  std::unique_ptr<NearestPointIndex>* index = nullptr;  // the index over A (backward direction)
};

// The comparison of A (summarised as `summary_a`) with B, both validated and with vertices.
ComparisonResult compare_prepared(const TriMesh& a, const MeshSummary& summary_a, const TriMesh& b,
                                  const CompareOptions& options, const std::string& label_b,
                                  const ReferenceStores& stores, Clock::time_point start) {
  const std::string& label_a = summary_a.label;
  ComparisonResult r;
  r.options = options;
  r.a = summary_a;
  r.b = summarize(b, label_b, options.threads);
  r.diagonal = r.a.box.diagonal();

  AttributeOptions attribute_options = options.attributes;
  attribute_options.threads = options.threads;
  AttributePlan plan =
      plan_attributes(a, b, attribute_options, label_a, label_b, stores.attributes);
  r.measures = plan.measures;
  r.normal_source = plan.normal_source;

  const SamplingOptions sampling = resolved_sampling(options, a, b);
  if (options.direction != Direction::kBackward)
    r.forward = run_direction(plan.a, plan.b, r.measures, options, sampling, r.diagonal, label_a,
                              label_b, stores.samples, nullptr);
  if (options.direction != Direction::kForward)
    r.backward = run_direction(plan.b, plan.a, r.measures, options, sampling, r.diagonal, label_b,
                               label_a, nullptr, stores.index);
  if (r.forward && r.backward) {
    for (std::size_t m = 0; m < r.measures.size(); ++m) {
      const Statistics& f = r.forward->stats[m];
      const Statistics& g = r.backward->stats[m];
      SymmetricStats s;
      s.min = 0.5 * (f.min + g.min);
      s.max = 0.5 * (f.max + g.max);
      s.mean = 0.5 * (f.mean + g.mean);
      s.rms = 0.5 * (f.rms + g.rms);
      s.stddev = 0.5 * (f.stddev + g.stddev);
      s.p50 = 0.5 * (f.p50 + g.p50);
      s.p90 = 0.5 * (f.p90 + g.p90);
      s.p95 = 0.5 * (f.p95 + g.p95);
      s.p99 = 0.5 * (f.p99 + g.p99);
      s.hausdorff = std::max(f.max, g.max);
      r.symmetric.push_back(s);
    }
  }
  r.seconds = seconds_since(start);
  return r;
}

// The thread count a comparison may run on, or InvalidInput naming `what`.
void check_threads(int threads, const std::string& what) {
  if (threads < 0 || threads > kMaxThreads)
    throw InvalidInput(what + " must be between 0 (OpenMP's default) and " +
                       std::to_string(kMaxThreads) + " (got " + std::to_string(threads) + ")");
}

// The options checked before any work: the thread count and the histogram (a billion bins ended
// in std::bad_alloc). The others are checked where they are used: the sampling step by the
// samplers, the tie tolerances by the index.
void check_options(const CompareOptions& o) {
  check_threads(o.threads, "threads");
  if (o.histogram_bins < 1 || o.histogram_bins > kMaxHistogramBins)
    throw InvalidInput("histogram_bins must be between 1 and " + std::to_string(kMaxHistogramBins) +
                       " (got " + std::to_string(o.histogram_bins) + ")");
}

// A mesh a comparison can take: validate()'s checks, and at least one vertex (InvalidInput
// naming `label` otherwise). O(V + F).
void require_comparable(const TriMesh& m, const std::string& label, int threads) {
  validate(m, label, threads);
  if (m.positions.empty()) throw InvalidInput(label + " has no vertices");
}

// Whether two sampling options give the same samples of one mesh (the thread count does not
// change them). O(1).
bool same_samples(const SamplingOptions& x, const SamplingOptions& y) {
  return x.vertices == y.vertices && x.edges == y.edges && x.faces == y.faces && x.step == y.step &&
         x.step_fraction == y.step_fraction && x.target_count == y.target_count && x.seed == y.seed;
}

// Whether two comparisons' options build the same index over one mesh. O(1).
bool same_index(IndexKind kind, const TieOptions& ties, const CompareOptions& o) {
  return kind == o.index && ties.relative == o.ties.relative &&
         ties.absolute_fraction == o.ties.absolute_fraction;
}

}  // namespace

struct ComparisonReference::Cache {
  ReferenceAttributes attributes;
  SamplingOptions sampling;                // what `samples` was made with
  std::optional<SampleSequence> samples;   // A's samples for the forward direction
  IndexKind index_kind = IndexKind::kBvh;  // what `index` was made with
  TieOptions ties;
  std::unique_ptr<NearestPointIndex> index;  // over A, for the backward direction
};

ComparisonReference::ComparisonReference(const TriMesh& a, std::string label, int threads)
    : mesh_(&a), label_(std::move(label)), cache_(std::make_unique<Cache>()) {
  check_threads(threads, "threads");
  require_comparable(a, label_, threads);
  summary_ = summarize(a, label_, threads);
}

ComparisonReference::~ComparisonReference() = default;

ComparisonResult compare_meshes(ComparisonReference& a, const TriMesh& b,
                                const CompareOptions& options, const std::string& label_b) {
  const auto start = Clock::now();
  check_options(options);
  require_comparable(b, label_b, options.threads);
  ComparisonReference::Cache& cache = *a.cache_;
  // What was kept is used only for the options that made it.
  const SamplingOptions sampling = resolved_sampling(options, a.mesh(), b);
  if (cache.samples && !same_samples(cache.sampling, sampling)) cache.samples.reset();
  if (!cache.samples) cache.sampling = sampling;
  if (cache.index && !same_index(cache.index_kind, cache.ties, options)) cache.index.reset();
  if (!cache.index) {
    cache.index_kind = options.index;
    cache.ties = options.ties;
  }
  return compare_prepared(a.mesh(), a.summary(), b, options, label_b,
                          {&cache.attributes, &cache.samples, &cache.index}, start);
}

ComparisonResult compare_meshes(const TriMesh& a, const TriMesh& b, const CompareOptions& options,
                                const std::string& label_a, const std::string& label_b) {
  const auto start = Clock::now();
  check_options(options);
  // A, then B: the order ComparisonReference checks them in.
  require_comparable(a, label_a, options.threads);
  require_comparable(b, label_b, options.threads);
  return compare_prepared(a, summarize(a, label_a, options.threads), b, options, label_b, {},
                          start);
}

}  // namespace meshdev
