#pragma once
// The attribute deviation of every sample (paper Eq. 3-4): for sample p on the reference mesh,
// the nearest points p' on the target surface and, per measure, d_i(p) = ||f_i(p) - f_i(p')||,
// the minimum over all equidistant p' (the paper's tie rule, §3.1). Texture-colour measures compare
// the texture images at the UVs of p and p' (minimum over ties); Cohen's texture deviation is not
// a nearest-point measure: p'' is the point of the target with p's UV (metric/texture_deviation.h).
#include <cstdint>
#include <vector>

#include "metric/attributes.h"
#include "metric/nearest_point.h"
#include "metric/raw_storage_allocator.h"
#include "metric/sampling.h"

namespace meshdev {

struct DeviationOptions {
  int threads = 0;  // OpenMP threads; 0 = OpenMP's default (OMP_NUM_THREADS or all cores)
  // Fill SampleDeviations::nearest (64 bytes per sample). compare() asks for it only when
  // per-sample output is kept; the statistics need only nearest_feature.
  bool keep_nearest = true;
  // References whose faces and per-vertex channels take at least this many bytes get those
  // channels' values prefetched a batch of queries ahead, and targets whose per-vertex channels
  // do get theirs prefetched at each batch's answers before they are read: several times the
  // 1-2 MB of a core's own cache, below which the values are mostly in cache already. Speed
  // only: the results do not depend on it (0: always).
  std::size_t prefetch_bytes = std::size_t{8} << 20;
};

// A per-sample array of compute_deviations's result. Its storage is left raw by the resize
// (metric/raw_storage_allocator.h), and every element is then written once, by the thread that
// computes that sample: zero-filling the arrays first (37 MB for a million samples and four
// measures) took 2-3 % of a 2-thread run even where the allocator reused touched memory
// (docs/performance-log.md §3). Read it like any vector; the statistics take it as a ConstSpan.
template <class T>
using PerSample = std::vector<T, RawStorageAllocator<T>>;
using DeviationArray = PerSample<double>;

struct SampleDeviations {
  std::vector<DeviationArray> values;  // values[measure][sample], measure 0 = geometry
  std::vector<SurfaceHit> nearest;     // per sample: the tie with the lowest face index
                                       // (only with DeviationOptions::keep_nearest)
  PerSample<Feature> nearest_feature;  // per sample: where that point lies on its face
  PerSample<std::uint32_t> tie_count;  // per sample: number of equidistant target faces
  // Whether the samples were queried in the order of their coarse Morton cells (a stored set
  // whose own order was not spatially coherent, e.g. shuffled) rather than in chunks of their own
  // order. Speed only; the samplers' sets come along a curve and never need it.
  bool cell_order = false;
  // The samples each thread of the team answered (one entry per thread). The threads share the
  // chunks until none is left, so the split follows their speeds: about even where the cores run
  // at one speed, uneven where one ran slower (a core shared with another program or guest).
  // Diagnostics only; the results do not depend on it.
  std::vector<std::size_t> samples_per_thread;
  // Only when Cohen's texture deviation is measured (see metric/texture_deviation.h):
  std::vector<std::uint8_t> cohen_case;  // per sample: a CohenCase
  std::size_t cohen_multiple = 0;        // samples whose UV lies at several distinct points of B
  std::size_t cohen_outside = 0;         // samples whose UV lies on no face of B
  double cohen_max_uv_gap = 0;           // largest UV distance of an outside sample to B's UVs
};

// The query hint of sample `s` of `reference` (QueryHint::source_mesh): its triangle, by index
// (`reference` must outlive the hint), and its barycentrics; no source for vertex samples of
// point clouds. O(1).
QueryHint sample_hint(const TriMesh& reference, const Sample& s);

// The bytes compute_deviations allocates per sample for `measures` with `options`: each
// measure's value, the feature and the tie count, the nearest point where kept, and Cohen's case
// and UV gap where measured. O(measures).
double deviation_bytes_per_sample(const std::vector<Measure>& measures,
                                  const DeviationOptions& options);

// Throws InvalidInput (check_fits_in_memory, metric/memory_limit.h) where `samples` times
// deviation_bytes_per_sample plus `extra_bytes_per_sample` (a caller's own per-sample arrays,
// e.g. compare's weights) exceed the memory available: compute_deviations makes this check
// with no extra, a caller may make it earlier, before building the index. O(measures).
void check_deviations_fit_in_memory(std::size_t samples, const std::vector<Measure>& measures,
                                    const DeviationOptions& options,
                                    double extra_bytes_per_sample = 0.0);

// Deviation of each sample of `reference` against `target` (whose index is `index`), for every
// measure of `measures` (measure 0 must be geometry). Units: those of each measure (absolute).
// Results do not depend on the thread count: each sample's result depends only on the sample.
// Throws InvalidInput, before anything is allocated or queried, where the samples' results
// cannot fit (check_deviations_fit_in_memory).
// O(samples x query cost x (1 + ties x attribute dims)).
SampleDeviations compute_deviations(const SampleSet& samples, const PreparedMesh& reference,
                                    const PreparedMesh& target, const NearestPointIndex& index,
                                    const std::vector<Measure>& measures,
                                    const DeviationOptions& options = {});

// The same for Monte Carlo samples made a chunk at a time as they are queried, instead of read
// from a stored set: the result, bit for bit, of compute_deviations on the SampleSet of those
// samples (sample_surface with Monte Carlo face sampling alone), without its 72 bytes per
// sample. The samples come along a Morton curve (metric/sampling.h) and are queried in chunks
// of their own order (never in the cell order). `samples.mesh()` must be `reference`'s mesh.
// O(as above).
SampleDeviations compute_deviations(const MonteCarloSamples& samples, const PreparedMesh& reference,
                                    const PreparedMesh& target, const NearestPointIndex& index,
                                    const std::vector<Measure>& measures,
                                    const DeviationOptions& options = {});

// The same for any samples a SampleSequence makes (vertices and scan-conversion or Monte Carlo
// face samples, as compare_meshes samples by default): the result, bit for bit, of
// compute_deviations on the SampleSet sample_surface stores for the same options. `samples.mesh()`
// must be `reference`'s mesh. O(as above).
SampleDeviations compute_deviations(const SampleSequence& samples, const PreparedMesh& reference,
                                    const PreparedMesh& target, const NearestPointIndex& index,
                                    const std::vector<Measure>& measures,
                                    const DeviationOptions& options = {});

}  // namespace meshdev
