#pragma once
// Sample points on a mesh's surface (the measurement points of the paper's Eq. 4).
//
// Kinds, combinable:
//  - vertices: every referenced vertex (every vertex if the mesh has no faces: a point cloud);
//  - edges:    points at the centres of equal steps along every edge (step Δ);
//  - faces, scan conversion (paper §4, Eq. 5-6): on face (A,B,C) the points
//              A + iΔ·AB/|AB| + jΔ·AC/|AC| for integers i, j >= 0 inside the triangle, i.e.
//              barycentrics s = iΔ/|AB|, t = jΔ/|AC| with s + t <= 1 (i <= n_u = |AB|/Δ,
//              j <= n_v = |AC|/Δ). Every face gets at least its corner A;
//  - faces, Monte Carlo: area-uniform random points; face f gets floor(N·area_f/area + u_f)
//              points, u_f uniform in [0,1); the random numbers of point k on face f are a hash
//              of (seed, f, k), so the set does not depend on the thread count.
// Order: vertex samples first, then edge samples, then face samples. Vertices, and faces (by
// their centroids), are visited along a Morton curve over the mesh's box, so that consecutive
// samples lie near each other whatever order the file stores them in: the nearest-point queries
// run in chunks of consecutive samples, and on a mesh stored in no spatial order a chunk made in
// index order covered faces from all over it (the default samples' queries 1.11-1.13 times as
// slow on buildings.ply, 1.38 times on armadillo: docs/performance-log.md §3). Edge samples follow
// their edges' vertex indices. Each face's samples are consecutive, in the order its kind makes
// them.
//
// Weights (for area-weighted statistics): face samples carry area_f / (samples on f); when a set
// has face samples, its vertex and edge samples carry weight 0 (they hunt the maximum but do not
// bias the mean); without face samples, edge samples carry length/(samples on the edge) and vertex
// samples 1 when alone.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "metric/mesh.h"
#include "metric/nearest_point.h"
#include "metric/raw_storage_allocator.h"

namespace meshdev {

enum class SampleKind : std::uint8_t { kVertex = 0, kEdge = 1, kFace = 2 };
const char* sample_kind_name(SampleKind k);

enum class FaceSampling : std::uint8_t {
  kNone,            // no face samples
  kScanConversion,  // the paper's regular 3D scan conversion with step Δ (deterministic)
  kMonteCarlo,      // area-uniform random points (seeded)
};

struct SamplingOptions {
  bool vertices = true;                                // sample the referenced vertices
  bool edges = false;                                  // sample along the edges with step Δ
  FaceSampling faces = FaceSampling::kScanConversion;  // how to sample face interiors
  double step = 0;               // Δ in absolute units; 0 = from step_fraction or the count
  double step_fraction = 0;      // Δ as a fraction of `diagonal` (e.g. 0.005 = 0.5 %)
  std::size_t target_count = 0;  // face samples wanted; 0 = 10 x faces (Metro's default)
  std::uint64_t seed = 1;        // Monte Carlo only
  int threads = 0;               // OpenMP threads for face samples (0 = OpenMP's default);
                                 // the set is the same for any count
};

struct Sample {
  Vec3 point;
  std::uint32_t face = kNoFace;         // the face it lies on (kNoFace for a point-cloud vertex)
  std::uint32_t vertex = kNoFace;       // the vertex, for vertex samples
  std::array<double, 3> bary{1, 0, 0};  // on `face`'s corners
  double weight = 1;                    // area weight (see above)
  SampleKind kind = SampleKind::kVertex;
};

// The storage of SampleSet::samples (metric/raw_storage_allocator.h): the face samplers resize
// once and then place every sample (placement new) on the threads that compute them, instead of
// value-initialising 72 bytes per sample on one thread first. Nothing may read an element that
// `resize` added before it is placed.
template <class T>
using SampleAllocator = RawStorageAllocator<T>;
using SampleVector = std::vector<Sample, SampleAllocator<Sample>>;

struct SampleSet {
  SampleVector samples;  // vertex samples first, then edge samples, then face samples
  double step = 0;       // the Δ actually used (absolute), 0 if none was needed
  std::size_t vertex_count = 0, edge_count = 0, face_count = 0;
  // Where sample_surface knows every sample weighs the same (Monte Carlo face samples alone, or
  // vertices alone), that weight, so the statistics need not gather it; 0 = read each sample's.
  double equal_weight = 0;
  std::string description;  // human-readable summary of what was sampled
};

// The Monte Carlo face samples of a mesh (FaceSampling::kMonteCarlo: face f gets
// floor(N·area_f/area + u_f) area-uniform points) as a sequence that makes any range of them on
// demand: exactly the samples, in the same order, that sample_surface gives for Monte Carlo face
// sampling alone, which makes them through this class. compare_meshes streams them (through
// SampleSequence, below) to compute_deviations a chunk at a time instead of storing the set (72
// bytes per sample, which a 1M-sample direction first had to fault in: docs/performance-log.md §3,
// thirteenth session). `mesh` must outlive it. Holds one offset and one face per face (12 bytes),
// the faces in the visit order (detail::face_visit_order); the samples
// weigh weight() each.
class MonteCarloSamples {
 public:
  // Counts every face's samples for `target` samples in all and `seed` (the counts on `threads`;
  // the same for any count). A mesh of zero area has none; throws InvalidInput where the area
  // overflows double. O(F).
  MonteCarloSamples(const TriMesh& mesh, std::size_t target, std::uint64_t seed, int threads);

  std::size_t size() const { return first_.back(); }  // N ± a few (rounding per face)
  double weight() const { return weight_; }           // of every sample: area / target
  std::uint64_t seed() const { return seed_; }
  const TriMesh& mesh() const { return *mesh_; }

  // Samples [begin, begin + count) into out[0, count). Precondition: begin + count <= size().
  // O(count + log F).
  void generate(std::size_t begin, std::size_t count, Sample* out) const;
  // Every sample into out[0, size()), on `threads` (0 = OpenMP's default; the same for any
  // count). out may be raw storage. O(size() + F).
  void generate_all(Sample* out, int threads) const;
  // Sample i. O(log F).
  Sample at(std::size_t i) const;
  // "N face points (Monte Carlo, seed S)", as SampleSet::description says it.
  std::string description() const;

 private:
  const TriMesh* mesh_;
  std::uint64_t seed_;
  double weight_ = 0;
  std::vector<std::uint32_t> order_;  // the faces in the visit order (detail::face_visit_order)
  std::vector<std::size_t> first_;    // first_[k]: the first sample of face order_[k]; [F]: size()
};

// The samples sample_surface(mesh, options, diagonal) gives for options without edge samples
// (vertices, scan-conversion or Monte Carlo face samples, alone or together), made on demand:
// the same samples, weights and order, bit for bit, without storing them (72 bytes per sample,
// which a direction had to fault in: 300 MB for the 4.2M default samples of buildings.ply).
// compare_meshes streams them through compute_deviations a chunk at a time. Holds 12 bytes per
// referenced vertex and 12 per face. `mesh` must outlive it.
class SampleSequence {
 public:
  // Throws InvalidInput as sample_surface does. Precondition: !options.edges (sequence_sampling).
  // O(F + V) on options.threads, plus the step search where the step is solved for a count.
  SampleSequence(const TriMesh& mesh, const SamplingOptions& options, double diagonal);

  std::size_t size() const { return vertices_.size() + face_count_; }
  std::size_t vertex_count() const { return vertices_.size(); }
  std::size_t face_count() const { return face_count_; }
  double step() const { return step_; }                  // as SampleSet::step
  double equal_weight() const { return equal_weight_; }  // as SampleSet::equal_weight
  const std::string& description() const { return description_; }
  const TriMesh& mesh() const { return *mesh_; }

  // Samples [begin, begin + count) into out[0, count) (raw storage allowed). Precondition:
  // begin + count <= size(). O(count + log F + the rows of the first face).
  void generate(std::size_t begin, std::size_t count, Sample* out) const;
  // Every sample into out[0, size()), on `threads` (0 = OpenMP's default). O(size() + F).
  void generate_all(Sample* out, int threads) const;
  // Sample i. O(log F + rows of its face).
  Sample at(std::size_t i) const;
  // Every sample's weight (Sample::weight) into out[0, size()), on `threads`. O(size() + F).
  void weights(double* out, int threads) const;

 private:
  struct VertexRef {
    std::uint32_t vertex, face;  // face: the lowest face using the vertex (kNoFace: point cloud)
    std::uint8_t corner;         // the vertex's corner in that face
  };
  void generate_scan(std::size_t begin, std::size_t count, Sample* out) const;

  const TriMesh* mesh_;
  std::vector<VertexRef> vertices_;
  double vertex_weight_ = 1;                      // 0 where there are face samples
  std::optional<MonteCarloSamples> monte_carlo_;  // for Monte Carlo face samples
  // Scan conversion: the faces in the visit order, and first_[k], the first face sample of face
  // order_[k] ([F]: the count).
  std::vector<std::uint32_t> order_;
  std::vector<std::size_t> first_;
  std::size_t face_count_ = 0;
  double step_ = 0, equal_weight_ = 0;
  std::string description_;
};

// Whether `options` asks for samples SampleSequence can make (no edge samples). O(1).
bool sequence_sampling(const SamplingOptions& options);

// The most face samples, and the most edge samples, a sample set holds (each kind counted on its
// own): targets and steps that would make more are refused.
constexpr std::size_t kMaxSampleCount = std::size_t{1} << 31;

// The checks of `options` that do not depend on the mesh: a step that is negative or not finite,
// a target_count above kMaxSampleCount. Throws InvalidInput naming the option; every sampler
// makes them first, and a caller can make them before it has a mesh (the sweep's config). O(1).
void check_sampling_options(const SamplingOptions& options);

// Samples `mesh` as `options` says. `diagonal` scales step_fraction (pass the reference mesh's
// bbox diagonal so both directions of a comparison use the same absolute Δ). Throws InvalidInput
// for a non-positive step, or face/edge sampling on a mesh without faces, a step or target that
// would make more than kMaxSampleCount samples of a kind, or a set larger than the memory
// available (metric/memory_limit.h), before any sample is made.
// O(F + V + number of samples) time and memory; the Δ search for a target count is O(F log).
SampleSet sample_surface(const TriMesh& mesh, const SamplingOptions& options, double diagonal);

// Whether `options` asks for Monte Carlo face samples alone (no vertices, no edges): the set that
// MonteCarloSamples can make on demand. O(1).
bool monte_carlo_only(const SamplingOptions& options);

// The samples sample_surface(mesh, options, ·) gives, made on demand (precondition:
// monte_carlo_only(options); target_count 0 = 10 x faces, as there). Throws InvalidInput as
// sample_surface does. O(F).
MonteCarloSamples monte_carlo_samples(const TriMesh& mesh, const SamplingOptions& options);

// Sets vertices/edges/faces of `options` from a comma-separated list of "vertices", "edges",
// "faces" (scan conversion) and "montecarlo" (the CLI's and the sweep config's syntax). Throws
// InvalidInput for an unknown kind. O(length of the list).
void set_sample_kinds(SamplingOptions& options, const std::string& list);

// Number of scan-conversion points on one triangle with step Δ (Eq. 6), or 2^31 + 1 once it is
// more than 2^31 (the most sample_surface makes). O(min(|AB|/Δ, 2^31)).
std::size_t scan_conversion_count(const Vec3& a, const Vec3& b, const Vec3& c, double step);

namespace detail {
// The Δ sample_surface uses for `target` scan-conversion face samples when no step is given:
// bisection on Δ (in [guess/4, guess*4], widened by 4 until it holds the target) until the count
// is within 0.2 % of `target`, keeping the Δ whose count came closest (60 steps at most). With
// `settle`, faces whose count is the same at both ends of the interval are not counted again (the
// count of a face never grows with Δ): the same totals, so the same Δ, bit for bit, as without
// (the twin the tests compare it with). Counts on `threads`. O(F) per step without `settle`; with
// it, O(F) for the first steps, then the faces still changing (docs/metric.md, Complexity).
// Totals far past the target (64 x target + 4 F + 1024) are not counted to the end; throws
// InvalidInput if every step tried gave such a total (a needle far longer than the other faces).
double solve_scan_step(const TriMesh& mesh, std::size_t target, int threads, bool settle = true);

// The order face samples visit the faces in: the faces' centroids along a Morton curve over the
// box of the mesh's vertices (morton_order: 24 bits from the highest in which the codes differ;
// faces in one cell keep index order). Deterministic, the same for any `threads` (codes and
// sort on the team, 0 = OpenMP's default). O(F) time, 16 bytes per face of scratch.
std::vector<std::uint32_t> face_visit_order(const TriMesh& mesh, int threads);
// The order vertex samples visit the vertices in: every vertex's position along the same curve
// (unreferenced ones included; the samplers skip them). O(V).
std::vector<std::uint32_t> vertex_visit_order(const TriMesh& mesh, int threads);
}  // namespace detail

}  // namespace meshdev
