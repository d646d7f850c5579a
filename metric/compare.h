#pragma once
// Mesh comparison with the attribute deviation metric: sample A, find the nearest points on B,
// measure every attribute, summarise; and the same from B to A. The paper's §3.3: the measure is
// not symmetric, so both directions are reported with their average and the symmetric maximum
// (Hausdorff distance for geometry).
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "metric/attribute_deviation.h"
#include "metric/attributes.h"
#include "metric/nearest_point.h"
#include "metric/sampling.h"
#include "metric/statistics.h"

namespace meshdev {

enum class Direction { kForward, kBackward, kBoth };  // A->B, B->A, both

// The most histogram bins a comparison makes per measure (CompareOptions::histogram_bins).
constexpr int kMaxHistogramBins = 1 << 20;
// The most OpenMP threads a comparison runs on (CompareOptions::threads, ComparisonReference):
// far more than cores, which only adds overhead, and below where creating them fails (100,000
// threads crashed the process with SIGSEGV inside OpenMP).
constexpr int kMaxThreads = 1024;

struct CompareOptions {
  SamplingOptions sampling;     // on each sampled mesh; the default target count is
                                // 10 x max(faces of A, faces of B) in both directions
  AttributeOptions attributes;  // what to measure (default: geometry, normal, shared channels)
  Direction direction = Direction::kBoth;
  IndexKind index = IndexKind::kBvh;  // kBruteForce is the O(F)-per-query oracle
  TieOptions ties;                    // when nearest points count as equidistant
  int threads = 0;  // OpenMP threads, 0 = default, at most kMaxThreads; results do not depend on it
  int histogram_bins = 32;    // of each measure's statistics, 1 to kMaxHistogramBins
  bool keep_samples = false;  // keep per-sample data (for --samples and --colored outputs)
};

struct MeshSummary {
  std::string label;
  std::size_t vertices = 0, referenced_vertices = 0, faces = 0, polygons = 0;
  double area = 0;
  BoundingBox box;
  std::vector<std::string> channels;
};

// Where a statistic's extreme was found.
struct Location {
  std::size_t sample = 0;
  Vec3 point;  // the sample on the sampled mesh
  SampleKind kind = SampleKind::kVertex;
  std::uint32_t face = kNoFace;  // its face on the sampled mesh
  Vec3 nearest;                  // the nearest point on the other mesh
  std::uint32_t nearest_face = kNoFace;
  Feature feature = Feature::kVertex;
  double value = 0;
};

struct DirectionResult {
  std::string from, to;  // labels of the sampled and the searched mesh
  std::string sampling;  // what was sampled
  double step = 0;       // Δ used (absolute), 0 if none
  std::size_t samples = 0;
  std::vector<Statistics> stats;                 // per measure
  std::vector<Location> max_location;            // per measure
  std::array<std::size_t, 3> nearest_feature{};  // samples whose nearest lies on a vertex/edge/face
  std::size_t samples_with_ties = 0;             // samples with more than one equidistant face
  // Cohen's texture deviation only (metric/texture_deviation.h): how F_b^-1(u, v) was resolved.
  std::size_t cohen_multiple = 0;  // samples whose UV lies at several distinct points of B (min)
  std::size_t cohen_outside = 0;   // samples whose UV lies on no face of B (UV-nearest point)
  double cohen_max_uv_gap = 0;     // the largest UV distance of such a sample to B's UVs
  double seconds_sampling = 0, seconds_index = 0, seconds_query = 0;
  std::string index;  // the nearest-point index used
  // Through a ComparisonReference: whether the samples (the step search) and the index were
  // those an earlier comparison made (their seconds then near 0).
  bool samples_reused = false, index_reused = false;
  // Only with keep_samples:
  SampleSet sample_set;
  SampleDeviations deviations;
};

// Per measure, both directions combined.
struct SymmetricStats {
  double min = 0, max = 0, mean = 0, rms = 0, stddev = 0, p50 = 0, p90 = 0, p95 = 0, p99 = 0;
  double hausdorff = 0;  // max of the two directions' maxima (symmetric Hausdorff for geometry)
};

struct ComparisonResult {
  MeshSummary a, b;
  std::vector<Measure> measures;
  std::string normal_source;
  double diagonal = 0;  // bbox diagonal of A: the divisor of every "relative" value
  std::optional<DirectionResult> forward, backward;
  std::vector<SymmetricStats> symmetric;  // only when both directions ran: average of the two
  double seconds = 0;
  CompareOptions options;
};

// Compares A (the reference) with B. Labels name the meshes in messages and reports.
// Throws InvalidInput for unusable inputs (non-finite data, no faces where a surface is needed,
// no samples, a requested attribute missing) and option values out of range (histogram bins,
// tie tolerances, sampling steps). Time: O(samples x query) plus O(F log F) builds.
ComparisonResult compare_meshes(const TriMesh& a, const TriMesh& b, const CompareOptions& options,
                                const std::string& label_a = "A", const std::string& label_b = "B");

// Mesh A checked and summarised once for comparisons with many meshes B (a sweep compares one
// mesh with each of its simplifications): compare_meshes(reference, b, ...) returns what
// compare_meshes(a, b, ...) returns, bit for bit except the seconds and DirectionResult's reuse
// flags, without doing again what depends on A alone. It keeps, made by the first comparison
// that needs them: A's computed normals and texture image; the samples of A (the step search of
// the forward direction), for samples made on demand (no edge samples, no keep_samples) and the
// same sampling options, which the default count 10 x max(faces of A, faces of B) keeps while B
// has no more faces than A; and the nearest-point index over A (the backward direction's
// target) for the same index kind and tie options. Holds them until destroyed (the BVH about 61
// bytes per face of A). `a` must outlive it, unchanged. Not thread-safe: one comparison at a time
// (each uses the OpenMP team inside).
class ComparisonReference {
 public:
  // Validates A (InvalidInput as compare_meshes throws it, naming `label`) and summarises it on
  // `threads` OpenMP threads (0 = the default, at most kMaxThreads; InvalidInput otherwise).
  // O(V + F).
  ComparisonReference(const TriMesh& a, std::string label, int threads = 0);
  ComparisonReference(const ComparisonReference&) = delete;
  ComparisonReference& operator=(const ComparisonReference&) = delete;
  ~ComparisonReference();

  const TriMesh& mesh() const { return *mesh_; }
  const std::string& label() const { return label_; }
  const MeshSummary& summary() const { return summary_; }

 private:
  friend ComparisonResult compare_meshes(ComparisonReference& a, const TriMesh& b,
                                         const CompareOptions& options, const std::string& label_b);
  struct Cache;
  const TriMesh* mesh_;
  std::string label_;
  MeshSummary summary_;
  std::unique_ptr<Cache> cache_;
};

// compare_meshes(a.mesh(), b, options, a.label(), label_b): the same result except the seconds
// and the reuse flags, reusing and filling a's kept values (see ComparisonReference). Throws as
// compare_meshes does. Time: that of compare_meshes less what a kept.
ComparisonResult compare_meshes(ComparisonReference& a, const TriMesh& b,
                                const CompareOptions& options, const std::string& label_b = "B");

// The summary of one mesh (counts, area, box, channels), on `threads` OpenMP threads (0: the
// default; the same summary for any team). Precondition: face indices in range (validate).
// O((V + F) / threads + F).
MeshSummary summarize(const TriMesh& mesh, const std::string& label, int threads = 1);

}  // namespace meshdev
