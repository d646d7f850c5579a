#include "metric/attribute_deviation.h"

#include <omp.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <memory>
#include <type_traits>

#include "metric/channel_chords.h"
#include "metric/chunk_schedule.h"
#include "metric/memory_limit.h"
#include "metric/morton_order.h"
#include "metric/plane_bounds.h"
#include "metric/simd2.h"
#include "metric/texture_deviation.h"
#include "metric/uv_index.h"

namespace meshdev {
namespace {

// The forms (metric/attributes.h) a list of measures compares values in: each distinct form is
// computed once per value, and measure k reads form form_of[k].
struct FormSet {
  ValueForm forms[3];
  int count = 0;
  std::vector<int> form_of;

  void add(MeasureKind kind) {
    const ValueForm f = value_form(kind);
    int i = 0;
    while (i < count && forms[i] != f) ++i;
    if (i == count) forms[count++] = f;
    form_of.push_back(i);
  }
  // Points out[i] at `value` in form i (the value itself for kRaw, else a transform in buf[i]).
  void transform(const double* value, int dim, double buf[3][16], const double* out[3]) const {
    for (int i = 0; i < count; ++i) {
      if (forms[i] == ValueForm::kRaw) {
        out[i] = value;
      } else {
        to_form(forms[i], value, dim, buf[i]);
        out[i] = buf[i];
      }
    }
  }
};

// Measures grouped by the channel they compare, so each channel is interpolated (and normalised
// or converted to CIELAB) once per point.
struct ChannelGroup {
  const AttributeChannel* reference = nullptr;
  const AttributeChannel* target = nullptr;
  std::vector<std::size_t> measures;
  std::vector<MeasureKind> kinds;  // measures[k]'s kind
  FormSet forms;
  // Every measure compares unit normals of a 3-D channel: the inline path (unit_normal and
  // unit_normal_distance, which to_form and form_distance use, so the same numbers).
  bool unit_normals = false;
  // Every measure compares the raw values (scalars, RGB, UVs) by Euclidean distance: the inline
  // path (form_distance's arithmetic, so the same numbers).
  bool raw = false;
};

std::vector<ChannelGroup> group_measures(const PreparedMesh& reference, const PreparedMesh& target,
                                         const std::vector<Measure>& measures) {
  std::vector<ChannelGroup> groups;
  for (std::size_t m = 1; m < measures.size(); ++m) {
    if (measures[m].kind == MeasureKind::kCohenTexture || is_texture_color(measures[m].kind))
      continue;  // handled separately: they look up images or B's parameterisation
    const AttributeChannel* ca = reference.channel(measures[m].channel);
    const AttributeChannel* cb = target.channel(measures[m].channel);
    assert(ca != nullptr && cb != nullptr && ca->dim == cb->dim);
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const ChannelGroup& g) { return g.reference == ca; });
    if (it == groups.end()) {
      groups.push_back({ca, cb, {}, {}, {}});
      it = groups.end() - 1;
    }
    it->measures.push_back(m);
    it->kinds.push_back(measures[m].kind);
    it->forms.add(measures[m].kind);
  }
  for (ChannelGroup& g : groups) {
    g.unit_normals = g.reference->dim == 3 &&
                     std::all_of(g.kinds.begin(), g.kinds.end(), is_unit_normal_measure);
    g.raw = std::all_of(g.kinds.begin(), g.kinds.end(),
                        [](MeasureKind k) { return value_form(k) == ValueForm::kRaw; });
  }
  return groups;
}

// A channel group whose deviations the loop computes inline (inline_groups): per-vertex values
// on both meshes, compared as unit normals of dimension 3 or as raw values by Euclidean
// distance, the two inline paths of ChannelGroup. Its values are read, and its measures'
// per-sample columns written, through plain pointers.
struct InlineGroup {
  const double* reference = nullptr;  // the reference's per-vertex values, dim per vertex
  const double* target = nullptr;     // the target's
  int dim = 0;
  bool unit_normals = false;     // else raw
  std::vector<double*> columns;  // out.values[m].data() of each measure m of the group
  std::vector<MeasureKind> kinds;
};

// The groups as InlineGroups, or none if any of them is not of that kind. `values`: the
// per-sample columns, already sized (their data pointers are kept).
std::vector<InlineGroup> inline_groups(const std::vector<ChannelGroup>& groups,
                                       std::vector<DeviationArray>& values) {
  std::vector<InlineGroup> inline_path;
  for (const ChannelGroup& g : groups) {
    if (g.reference->storage != Storage::kPerVertex || g.target->storage != Storage::kPerVertex ||
        !(g.unit_normals || g.raw))
      return {};
    InlineGroup f;
    f.reference = g.reference->values.data();
    f.target = g.target->values.data();
    f.dim = g.reference->dim;
    f.unit_normals = g.unit_normals;
    for (std::size_t m : g.measures) f.columns.push_back(values[m].data());
    f.kinds = g.kinds;
    inline_path.push_back(std::move(f));
  }
  return inline_path;
}

// Component k of per-vertex `values` (dim per vertex) at barycentrics `bary` of the triangle
// with corners `t` (barycentric_mix, as interpolate). O(1).
inline double mix(const double* values, int dim, const Triangle& t,
                  const std::array<double, 3>& bary, int k) {
  const std::size_t d = static_cast<std::size_t>(dim);
  return barycentric_mix(bary, values + t[0] * d, values + t[1] * d, values + t[2] * d, k);
}

// The Euclidean distance between a raw group's values at barycentrics `bary_a` of the
// reference's face `ta` and `bary_b` of the target's face `tb`: the squared differences summed in
// component order, as form_distance sums them. Dim > 0: the group's dimension as a constant, so
// the loop unrolls without its set-up (the general loop cost as much for one scalar as for
// three); Dim = 0: `run_dim` at run time. O(dim).
template <int Dim>
double raw_distance(const InlineGroup& g, const Triangle& ta, const std::array<double, 3>& bary_a,
                    const Triangle& tb, const std::array<double, 3>& bary_b, int run_dim = 0) {
  const int dim = Dim > 0 ? Dim : run_dim;
  double sum = 0.0;
  for (int c = 0; c < dim; ++c) {
    const double d = mix(g.reference, dim, ta, bary_a, c) - mix(g.target, dim, tb, bary_b, c);
    sum += d * d;
  }
  return std::sqrt(sum);
}

// A sample whose deviations the inline path computes: its face and barycentrics on the
// reference, its one tie's on the target, and its index in the result.
struct InlineSample {
  const Triangle* ta;
  const std::array<double, 3>* bary_a;
  const Triangle* tb;
  const std::array<double, 3>* bary_b;
  std::size_t i;
};

// Writes sample x's deviations of inline group g: from the reference's values at its
// barycentrics of its face and the target's at those of its tie's face. The numbers of the
// general path (interpolate, unit_normal, unit_normal_distance, the raw Euclidean distance), bit
// for bit, without its per-sample dispatch on storage, dimension and form: torus100k -> 1m
// +2.8 %, armadillo -> 5k +6.6 % (docs/performance-log.md §3). The normals' chord |n - m| is
// computed once for both normal measures, and raw groups of 1 to 3 values take their unrolled
// distance: the two together torus1m -> 100k +2.8 %, torus100k -> 10k +1.5 %, torus100k -> 1m
// +0.7 % (chunk-interleaved, docs/performance-log.md §3). The loop takes samples two at a time
// (inline_deviations_pair); this is for an odd one out and for groups the pair leaves. O(dim +
// measures).
void group_deviations(const InlineGroup& g, const InlineSample& x) {
  const Triangle &ta = *x.ta, &tb = *x.tb;
  const std::array<double, 3>&bary_a = *x.bary_a, &bary_b = *x.bary_b;
  if (g.unit_normals) {
    const Vec3 na =
        unit_normal({mix(g.reference, 3, ta, bary_a, 0), mix(g.reference, 3, ta, bary_a, 1),
                     mix(g.reference, 3, ta, bary_a, 2)});
    const Vec3 nb = unit_normal({mix(g.target, 3, tb, bary_b, 0), mix(g.target, 3, tb, bary_b, 1),
                                 mix(g.target, 3, tb, bary_b, 2)});
    const double chord = norm(na - nb);
    for (std::size_t k = 0; k < g.columns.size(); ++k)
      g.columns[k][x.i] = unit_normal_distance(g.kinds[k], chord, na, nb);
    return;
  }
  double d;
  switch (g.dim) {
    case 1:
      d = raw_distance<1>(g, ta, bary_a, tb, bary_b);
      break;
    case 2:
      d = raw_distance<2>(g, ta, bary_a, tb, bary_b);
      break;
    case 3:
      d = raw_distance<3>(g, ta, bary_a, tb, bary_b);
      break;
    default:
      d = raw_distance<0>(g, ta, bary_a, tb, bary_b, g.dim);
  }
  for (double* column : g.columns) column[x.i] = d;
}

// mix for two samples at once, x's in lane 0 and y's in lane 1: barycentric_mix's operations in
// its order on each lane. O(1).
inline simd::D2 mix2(const double* values, int dim, const InlineSample& x, const InlineSample& y,
                     bool target, int k) {
  using simd::D2;
  const std::size_t d = static_cast<std::size_t>(dim);
  const Triangle &tx = target ? *x.tb : *x.ta, &ty = target ? *y.tb : *y.ta;
  const std::array<double, 3>&bx = target ? *x.bary_b : *x.bary_a,
                           &by = target ? *y.bary_b : *y.bary_a;
  D2 r = D2::pair(bx[0], by[0]) * D2::pair(values[tx[0] * d + k], values[ty[0] * d + k]);
  r = r + D2::pair(bx[1], by[1]) * D2::pair(values[tx[1] * d + k], values[ty[1] * d + k]);
  return r + D2::pair(bx[2], by[2]) * D2::pair(values[tx[2] * d + k], values[ty[2] * d + k]);
}

// Two samples' 3-vectors, lane by lane, and dot2 as Vec3's dot: (x x' + y y') + z z'.
struct Vec3x2 {
  simd::D2 x, y, z;
};
inline simd::D2 dot2(const Vec3x2& a, const Vec3x2& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// unit_normal on each lane: (1 / |n|) n where |n| > 0, else 0. O(1).
inline Vec3x2 unit_normal2(const Vec3x2& n) {
  const simd::D2 len = simd::sqrt(dot2(n, n));
  const simd::M2 positive = simd::positive(len);
  const simd::D2 inverse = simd::D2::splat(1.0) / len;
  return {simd::keep(positive, inverse * n.x), simd::keep(positive, inverse * n.y),
          simd::keep(positive, inverse * n.z)};
}

// group_deviations of samples x and y for every group, each lane computing one sample with its
// operations in their order (metric/simd2.h: the same bits), the asin of the angle lane by lane.
// Two samples share each instruction of the interpolation, normalisation and chords, and their
// square roots and divisions run two at a time. With the target's values prefetched a batch
// ahead (deviations_of), against the scalar path one sample at a time, chunk-interleaved on
// 2 threads: torus100k -> 1m +2.1 / +3.4 / +3.8 %, torus1m -> 100k +4.1 %, armadillo -> 5k
// +5.4 %, buildings -> 40k +4.6 %, bunny00 -> 7k +2.9 %, torus100k -> 10k -0.4 / +1.4 %
// (docs/performance-log.md §3). Groups of raw values of more than 3 components go one sample at a
// time. O(sum of dims + measures).
void inline_deviations_pair(const std::vector<InlineGroup>& groups, const InlineSample& x,
                            const InlineSample& y) {
  using simd::D2;
  for (const InlineGroup& g : groups) {
    double lane[2];
    if (g.unit_normals) {
      const Vec3x2 na = unit_normal2(Vec3x2{mix2(g.reference, 3, x, y, false, 0),
                                            mix2(g.reference, 3, x, y, false, 1),
                                            mix2(g.reference, 3, x, y, false, 2)});
      const Vec3x2 nb =
          unit_normal2(Vec3x2{mix2(g.target, 3, x, y, true, 0), mix2(g.target, 3, x, y, true, 1),
                              mix2(g.target, 3, x, y, true, 2)});
      const Vec3x2 difference{na.x - nb.x, na.y - nb.y, na.z - nb.z};
      const Vec3x2 sum{na.x + nb.x, na.y + nb.y, na.z + nb.z};
      double chord[2], across[2];
      simd::store(chord, simd::sqrt(dot2(difference, difference)));
      simd::store(across, simd::sqrt(dot2(sum, sum)));
      auto zero = [](const Vec3x2& n) {
        return simd::zero(n.x) & simd::zero(n.y) & simd::zero(n.z);
      };
      const int either_zero = simd::bits(zero(na) | zero(nb));
      for (std::size_t k = 0; k < g.columns.size(); ++k) {
        for (int l = 0; l < 2; ++l)
          lane[l] =
              unit_normal_distance(g.kinds[k], chord[l], across[l], (either_zero >> l & 1) != 0);
        g.columns[k][x.i] = lane[0];
        g.columns[k][y.i] = lane[1];
      }
      continue;
    }
    if (g.dim > 3) {
      group_deviations(g, x);
      group_deviations(g, y);
      continue;
    }
    D2 sum = D2::splat(0.0);  // raw_distance's sum of squares, in component order
    for (int c = 0; c < g.dim; ++c) {
      const D2 e = mix2(g.reference, g.dim, x, y, false, c) - mix2(g.target, g.dim, x, y, true, c);
      sum = sum + e * e;
    }
    simd::store(lane, simd::sqrt(sum));
    for (double* column : g.columns) {
      column[x.i] = lane[0];
      column[y.i] = lane[1];
    }
  }
}

// group_deviations of four samples for every group: the channels compared in the four lanes of
// channel_chords_x4 (the same bits), the angles' asin lane by lane here. `channels`: the groups
// as ChordChannels, channels[j] for groups[j]. Groups of raw values of more than 3 components go
// one sample at a time. Precondition: the CPU runs AVX2 (simd_level() != kBaseline). O(sum of
// dims + measures).
void inline_deviations_x4(const std::vector<InlineGroup>& groups,
                          const std::vector<detail::ChordChannel>& channels,
                          std::vector<detail::ChannelChords>& chords, const InlineSample s[4]) {
  detail::ChordSample lanes[4];
  for (int l = 0; l < 4; ++l)
    lanes[l] = {s[l].ta->data(), s[l].bary_a->data(), s[l].tb->data(), s[l].bary_b->data()};
  detail::channel_chords_x4(channels.data(), channels.size(), lanes, chords.data());
  for (std::size_t j = 0; j < groups.size(); ++j) {
    const InlineGroup& g = groups[j];
    const detail::ChannelChords& c = chords[j];
    if (!g.unit_normals && g.dim > 3) {
      for (int l = 0; l < 4; ++l) group_deviations(g, s[l]);
      continue;
    }
    for (std::size_t k = 0; k < g.columns.size(); ++k)
      for (int l = 0; l < 4; ++l)
        g.columns[k][s[l].i] = g.unit_normals
                                   ? unit_normal_distance(g.kinds[k], c.chord[l], c.across[l],
                                                          (c.either_zero >> l & 1) != 0)
                                   : c.chord[l];
  }
}

// One query's ties inside a BatchHits.
struct TieRange {
  const SurfaceHit* first;
  std::size_t count;
  const SurfaceHit* begin() const { return first; }
  const SurfaceHit* end() const { return first + count; }
  std::size_t size() const { return count; }
  const SurfaceHit& front() const { return *first; }
  const SurfaceHit& operator[](std::size_t k) const { return first[k]; }
};

constexpr std::size_t kChunk = 1024;  // samples per scheduling unit (consecutive = coherent)

// Where compute_deviations reads its samples from: a stored set, or Monte Carlo samples made a
// chunk at a time. at(i): sample i; GeneratedSamples::chunk(begin, count, scratch): samples
// begin .. begin + count - 1, made in scratch.
struct StoredSamples {
  const SampleSet& set;
  std::size_t size() const { return set.samples.size(); }
  const Sample& at(std::size_t i) const { return set.samples[i]; }
};

// A chunk's samples, j = 0 .. count - 1: base[j], or base[visit[j]] in the cell order.
struct ChunkSamples {
  const Sample* base;
  const std::uint32_t* visit;
  const Sample& operator[](std::size_t j) const { return visit ? base[visit[j]] : base[j]; }
};

// Samples made on demand by a MonteCarloSamples or a SampleSequence.
template <class Source>
struct GeneratedSamples {
  const Source& source;
  std::size_t size() const { return source.size(); }
  Sample at(std::size_t i) const { return source.at(i); }
  const Sample* chunk(std::size_t begin, std::size_t count, std::vector<Sample>& scratch) const {
    scratch.resize(count);
    source.generate(begin, count, scratch.data());
    return scratch.data();
  }
};
template <class T>
constexpr bool kIsGenerated = false;
template <class Source>
constexpr bool kIsGenerated<GeneratedSamples<Source>> = true;

}  // namespace

double deviation_bytes_per_sample(const std::vector<Measure>& measures,
                                  const DeviationOptions& options) {
  const bool cohen = std::any_of(measures.begin(), measures.end(), [](const Measure& m) {
    return m.kind == MeasureKind::kCohenTexture;
  });
  return static_cast<double>(measures.size() * sizeof(double) + sizeof(Feature) +
                             sizeof(std::uint32_t) +
                             (options.keep_nearest ? sizeof(SurfaceHit) : 0) +
                             (cohen ? sizeof(std::uint8_t) + sizeof(double) : 0));
}

void check_deviations_fit_in_memory(std::size_t samples, const std::vector<Measure>& measures,
                                    const DeviationOptions& options,
                                    double extra_bytes_per_sample) {
  check_fits_in_memory(static_cast<double>(samples) *
                           (deviation_bytes_per_sample(measures, options) + extra_bytes_per_sample),
                       "the deviations of " + std::to_string(samples) + " samples",
                       "use fewer samples or a larger sampling step");
}

QueryHint sample_hint(const TriMesh& reference, const Sample& s) {
  QueryHint hint;
  if (s.face == kNoFace) return hint;
  hint.source_mesh = &reference;
  hint.source_face = s.face;
  hint.source_bary = s.bary;
  return hint;
}

namespace {

// compute_deviations over `samples` (StoredSamples or GeneratedSamples; only stored sets are
// ever queried in the cell order below).
template <class Samples>
SampleDeviations deviations_of(const Samples& samples, const PreparedMesh& reference,
                               const PreparedMesh& target, const NearestPointIndex& index,
                               const std::vector<Measure>& measures,
                               const DeviationOptions& options) {
  constexpr bool kGenerated = kIsGenerated<Samples>;
  assert(!measures.empty() && measures[0].kind == MeasureKind::kGeometry);
  const std::size_t n = samples.size();
  SampleDeviations out;
  out.values.resize(measures.size());  // the per-sample arrays are made by the team, below
  const std::vector<ChannelGroup> groups = group_measures(reference, target, measures);
  const TriMesh& ref = *reference.mesh;
  const TriMesh& tgt = *target.mesh;
  const auto chunks = static_cast<std::int64_t>((n + kChunk - 1) / kChunk);
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();

  // Cohen's measure and texture colours: the texcoord channels, B's UV index, the images.
  std::vector<std::size_t> cohen, texture;
  for (std::size_t m = 1; m < measures.size(); ++m) {
    if (measures[m].kind == MeasureKind::kCohenTexture) cohen.push_back(m);
    if (is_texture_color(measures[m].kind)) texture.push_back(m);
  }
  check_deviations_fit_in_memory(n, measures, options);  // before any of it is allocated
  FormSet texture_forms;
  for (std::size_t m : texture) texture_forms.add(measures[m].kind);
  const AttributeChannel* uv_ref = reference.channel("texcoord");
  const AttributeChannel* uv_tgt = target.channel("texcoord");
  std::unique_ptr<UvIndex> uv_index;
  double same_point = 0.0;  // Cohen's "same point" distance: 1e-9 of B's diagonal
  if (!cohen.empty()) {
    same_point = 1e-9 * bounding_box(tgt).diagonal();
    assert(uv_ref != nullptr && uv_tgt != nullptr);
    uv_index = std::make_unique<UvIndex>(tgt, *uv_tgt);
    out.cohen_case.assign(n, 0);
  }
  if (!texture.empty()) assert(reference.texture && target.texture && uv_ref && uv_tgt);
  std::vector<double> uv_gap(cohen.empty() ? 0 : n, 0.0);
  // The grid of the Morton order each chunk is queried in: the box of the reference's vertices,
  // which holds its samples (up to rounding; morton_order clamps), on the team. (Vertices no
  // face uses can only make the grid coarser: speed, not results. The box of the faces' corners
  // took 2-6 ms for torus1m's 1M faces, 2-6 % of torus1m -> 100k's 2-thread query phase, the
  // vertices' 0.4-0.8 ms: docs/performance-log.md §3.)
  const BoundingBox sample_box = position_bounding_box(ref, threads);
  // Stored sets of more than one chunk whose order is not spatially coherent are first put in
  // order of their coarse Morton cells (a stable counting sort): a chunk cut from the bucket
  // order covers a few cells, which its own Morton order then walks. The samplers' sets
  // (sample_surface, and the samples made as they are queried) come along a Morton curve whatever
  // the order of the mesh's faces (metric/sampling.h) and are never reordered; sets made or
  // permuted elsewhere (a caller's, peer_compare's) may need it.
  // Where the order is coherent (faces stored along the surface, as most meshes store them) the
  // bucket order only costs: the samples and their results are then read and written out of
  // order (`meshdev compare` forward queries, 1M Monte Carlo samples, the cell order for every
  // dense set against only for incoherent ones: buildings 0.077-0.080 -> 0.059-0.063 s,
  // torus100k -> 10k 0.073 -> 0.063 s; torus1m with its faces shuffled keeps it, 0.12 s, and
  // took 0.47-0.51 s with it switched off; docs/performance-log.md §3). Coherence
  // is probed on pairs of consecutive samples: in a coherent order fewer than an eighth of them
  // lie in different cells of the 4 x 4 x 4 grid over the box (0-13 % on the test meshes), in a
  // shuffled one most do (64-85 %); a third is the threshold (a wrong guess costs speed only).
  // Pairs every 64 samples, at most 4096 of them (evenly spread): each pair is a cache miss, and
  // the 15,600 pairs of 1M samples took 0.5 ms, serial, ahead of the team's work (1 % of
  // torus100k -> 10k's 2-thread run); capped, 0.2-1.1 % faster on the dense pairs
  // (docs/performance-log.md §3). 4096 pairs give the fraction to 1 % (a standard error).
  // Only where samples are dense on B (at least kDense per face), where packets form and the
  // order pays: elsewhere queries go one by one and reading the samples and writing their
  // results out of order cost more (torus100k -> 1m: -7 %). `visit[k]` is the k-th sample
  // queried (empty: the k-th).
  std::vector<std::uint32_t> visit;
  const MortonGrid grid(sample_box);
  auto probe_incoherent = [&] {
    constexpr std::size_t kProbe = 64, kMaxPairs = 4096;
    constexpr int kCoarseShift = 3 * (MortonGrid::kBucketLevels - 2);  // 4 x 4 x 4 cells
    std::size_t pairs = 0, apart = 0;
    const std::size_t step = std::max(kProbe, n / kMaxPairs);
    for (std::size_t i = step; i < n; i += step, ++pairs)
      apart += grid.bucket(samples.at(i).point) >> kCoarseShift !=
               grid.bucket(samples.at(i - 1).point) >> kCoarseShift;
    return 3 * apart > pairs;
  };
  constexpr std::size_t kDense = 8;
  if constexpr (!kGenerated) {
    if (n > kChunk && n >= kDense * tgt.faces.size() && probe_incoherent()) {
      std::vector<std::uint32_t> bucket(n);
#pragma omp parallel for num_threads(threads) schedule(static)
      for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); ++i)
        bucket[i] = grid.bucket(samples.at(i).point);
      out.cell_order = stable_bucket_order(bucket.data(), n, visit);
    }
  }
  auto sample_at = [&visit](std::size_t k) -> std::size_t { return visit.empty() ? k : visit[k]; };
  // The samples queried k = begin .. begin + count - 1: made as they are queried, or read in
  // place, in the set's own order or through the cell order (generated samples never have one).
  auto chunk_of = [&](std::size_t begin, std::size_t count, std::vector<Sample>& scratch) {
    if constexpr (kGenerated) {
      return ChunkSamples{samples.chunk(begin, count, scratch), nullptr};
    } else {
      const Sample* all = samples.set.samples.data();
      return visit.empty() ? ChunkSamples{all + begin, nullptr}
                           : ChunkSamples{all, visit.data() + begin};
    }
  };
  // Whether the chunks prefetch the reference's per-vertex channel values (below).
  std::size_t reference_bytes = ref.faces.size() * sizeof(Triangle);
  for (const ChannelGroup& g : groups)
    if (g.reference->storage == Storage::kPerVertex)
      reference_bytes += g.reference->values.size() * sizeof(double);
  const bool prefetch_reference = reference_bytes >= options.prefetch_bytes;
  // And whether each batch prefetches the target's, at the one-tie answers' corners (below).
  std::size_t target_bytes = 0;
  for (const ChannelGroup& g : groups)
    if (g.target->storage == Storage::kPerVertex)
      target_bytes += g.target->values.size() * sizeof(double);
  const bool prefetch_target = target_bytes >= options.prefetch_bytes;
  // The inline path's samples per step: four in AVX lanes where the CPU runs them, else two.
#if defined(MESHDEV_X86_KERNELS)
  const int lanes = simd_level() != SimdLevel::kBaseline ? 4 : 2;
#else
  const int lanes = 2;
#endif

  // The per-sample output arrays of raw storage (PerSample) are only allocated: each sample's
  // values are written once, below, for every measure (geometry, each channel group's, Cohen's,
  // the texture colours'), so their pages are first touched by the threads that fill them.
  // Allocated here, by the calling thread, they come from its heap, where a program that keeps
  // freed memory (the meshdev program's mallopt) finds the blocks of its previous call: allocated
  // by the team's threads, each in its own arena, the second thread's block was faulted in afresh
  // at every call (peer_compare torus100k -> 10k, 1M samples, 2 threads: 1,970 -> 359 page faults
  // per further repeat; docs/performance-log.md §3).
  for (DeviationArray& values : out.values) values.resize(n);
  out.nearest_feature.resize(n);
  out.tie_count.resize(n);
  // The common case, every channel per vertex and compared inline (normals, scalars, colours
  // and UVs by Euclidean distance), for samples on faces with one tie; the rest below.
  const std::vector<InlineGroup> inline_path = cohen.empty() && texture.empty()
                                                   ? inline_groups(groups, out.values)
                                                   : std::vector<InlineGroup>{};
  std::vector<detail::ChordChannel> chord_channels;  // the same, for channel_chords_x4
  for (const InlineGroup& g : inline_path)
    chord_channels.push_back({g.reference, g.target, g.dim, g.unit_normals});
  // The chunks go to the team in contiguous ranges, with stealing at the end (ChunkSchedule):
  // consecutive chunks query the same part of B, so each thread keeps its caches (the plane
  // cache, its core's L2) on a part of its own. Dealt one by one as schedule(dynamic, 1) deals
  // them, neighbouring chunks went to different threads, which fetched and prepared the same
  // leaf blocks twice. Chunk-interleaved on 2 threads, bit for bit the same answers: +2.1-2.8 %
  // on torus100k -> 1m, +5.4-8.3 % on the other pairs (docs/performance-log.md §3).
  std::unique_ptr<ChunkSchedule> schedule;
#pragma omp parallel num_threads(threads)
  {
    // `nearest` is value-initialised, by one thread of the team while the others wait, and the
    // schedule made for the team the region has (the barrier of `single` orders both before the
    // chunks).
#pragma omp single
    {
      if (options.keep_nearest) out.nearest.resize(n);
      schedule = std::make_unique<ChunkSchedule>(chunks, omp_get_num_threads());
      out.samples_per_thread.assign(static_cast<std::size_t>(omp_get_num_threads()), 0);
    }
    BatchHits batch;
    std::vector<Vec3> points;
    std::vector<QueryHint> hints;
    std::vector<std::uint32_t> order;
    std::vector<std::uint64_t> keys;
    std::vector<double> best;
    std::vector<UvHit> uv_hits;
    std::vector<detail::ChannelChords> chords(chord_channels.size());
    std::vector<Sample> scratch;          // the chunk's samples, where they are not read in place
    double fa[16], fb[16];                // channel values at p and at p'
    double form_a[3][16], form_b[3][16];  // ... normalised or in CIELAB
    const double *at_a[3], *at_b[3];      // each form's values
    const int thread = omp_get_thread_num();
    std::size_t answered = 0;  // this thread's samples, for out.samples_per_thread
    for (std::int64_t chunk; (chunk = schedule->next(thread)) >= 0;) {
      // The chunk's nearest points in one batch, in Morton order of the samples' positions
      // (on a grid over A's box, so a set sorted on that grid is left as it is): consecutive
      // queries are then near each other (packets, tight hints) even where samples come in
      // random order inside large faces. Results go to each sample's own index, so the order
      // changes only the speed.
      const std::size_t begin = static_cast<std::size_t>(chunk) * kChunk;
      const std::size_t count = std::min(n, begin + kChunk) - begin;
      answered += count;
      points.resize(count);
      hints.resize(count);
      const ChunkSamples chunk_samples = chunk_of(begin, count, scratch);
      for (std::size_t j = 0; j < count; ++j) points[j] = chunk_samples[j].point;
      morton_order(points.data(), count, sample_box, order, keys);
      // The samples' positions and hints in that order. The reference's per-vertex channel
      // values at each sample's corners are prefetched here, a batch's queries before they are
      // read: where the order of the samples is not that of the reference's faces (samples
      // sorted along a curve, faces stored in no spatial order), reading them in the deviation
      // loop waited for one sample's cache misses at a time (its long body holds the processor's
      // window), and this short loop lets many be in flight. torus1m -> 100k (`peer_compare`,
      // Morton-sorted samples): +3.5 %; `meshdev compare` with torus1m's faces shuffled: the
      // forward queries -9 %; Morton-sorted samples on those shuffled faces +35 %. Only for
      // references of at least DeviationOptions::prefetch_bytes (faces and prefetched channels):
      // below, their values are mostly in cache and the prefetches cost about 1 % (torus100k,
      // 2.8 MB; docs/performance-log.md §3).
      for (std::size_t j = 0; j < count; ++j) {
        const Sample& s = chunk_samples[order[j]];
        points[j] = s.point;
        hints[j] = sample_hint(ref, s);
        if (s.face == kNoFace || !prefetch_reference) continue;
        const Triangle& corners = ref.faces[s.face];
        for (const ChannelGroup& g : groups)
          if (g.reference->storage == Storage::kPerVertex)
            for (int c = 0; c < 3; ++c) __builtin_prefetch(g.reference->element(corners[c]));
      }
      // A batch may stop early (BatchHits::kMaxHits ties held); the rest goes in the next one.
      for (std::size_t from = 0; from < count;) {
        const std::size_t to =
            from + index.find_batch(points.data() + from, hints.data() + from, count - from, batch);
        // The target's per-vertex values at the corners of each one-tie answer's face, which
        // the inline path reads below, prefetched for the whole batch first: samples sparse on a
        // large target each land on a face of their own, whose values the search never read
        // (torus100k -> 1m: 16 MB of normals and temperatures; with the scalar path, batched,
        // +3.0 % there, docs/performance-log.md §3). Only for targets of at least prefetch_bytes,
        // as the reference's above.
        if (prefetch_target && !inline_path.empty())
          for (std::size_t j = from; j < to; ++j) {
            if (batch.tie_count(j - from) != 1) continue;
            const Triangle& corners = tgt.faces[batch.ties_begin(j - from)->face];
            for (const InlineGroup& g : inline_path)
              for (int c = 0; c < 3; ++c)
                __builtin_prefetch(g.target + corners[c] * static_cast<std::size_t>(g.dim));
          }
        // Samples for the inline path go four (or two) at a time; they wait here.
        InlineSample held[4];
        int held_count = 0;
        for (std::size_t j = from; j < to; ++j) {
          const std::size_t i = sample_at(begin + order[j]);
          const Sample& s = chunk_samples[order[j]];
          const TieRange ties{batch.ties_begin(j - from), batch.tie_count(j - from)};
          assert(ties.size() > 0);
          if (options.keep_nearest) out.nearest[i] = ties.front();
          out.nearest_feature[i] = ties.front().feature;
          out.tie_count[i] = static_cast<std::uint32_t>(ties.size());
          out.values[0][i] = batch.distance[j - from];
          if (!inline_path.empty() && s.face != kNoFace && ties.size() == 1) {
            const InlineSample sample{&ref.faces[s.face], &s.bary, &tgt.faces[ties[0].face],
                                      &ties[0].bary, i};
            held[held_count++] = sample;
            if (held_count == lanes) {
              if (lanes == 4)
                inline_deviations_x4(inline_path, chord_channels, chords, held);
              else
                inline_deviations_pair(inline_path, held[0], held[1]);
              held_count = 0;
            }
            continue;
          }

          for (const ChannelGroup& g : groups) {
            const int dim = g.reference->dim;
            interpolate(*g.reference, ref, s.face, s.bary, s.vertex, fa);
            // Unit normals (normal, normal angle) inline, with the arithmetic form_distance uses;
            // every other channel through its forms.
            Vec3 na;
            if (g.unit_normals)
              na = unit_normal({fa[0], fa[1], fa[2]});
            else if (!g.raw)
              g.forms.transform(fa, dim, form_a, at_a);
            auto each_measure = [&](const SurfaceHit& h, auto&& use) {
              interpolate(*g.target, tgt, h.face, h.bary, kNoFace, fb);
              if (g.raw) {
                double sum = 0.0;
                for (int c = 0; c < dim; ++c) sum += (fa[c] - fb[c]) * (fa[c] - fb[c]);
                const double d = std::sqrt(sum);
                for (std::size_t k = 0; k < g.measures.size(); ++k) use(k, d);
                return;
              }
              if (g.unit_normals) {
                const Vec3 nb = unit_normal({fb[0], fb[1], fb[2]});
                const double chord = norm(na - nb);
                for (std::size_t k = 0; k < g.measures.size(); ++k)
                  use(k, unit_normal_distance(g.kinds[k], chord, na, nb));
                return;
              }
              g.forms.transform(fb, dim, form_b, at_b);
              for (std::size_t k = 0; k < g.measures.size(); ++k) {
                const int f = g.forms.form_of[k];
                use(k, form_distance(g.kinds[k], at_a[f], at_b[f], dim));
              }
            };
            if (ties.size() == 1) {  // the common case: no minimum to take
              each_measure(ties[0],
                           [&](std::size_t k, double d) { out.values[g.measures[k]][i] = d; });
              continue;
            }
            best.assign(g.measures.size(), std::numeric_limits<double>::infinity());
            for (const SurfaceHit& h : ties)
              each_measure(h, [&](std::size_t k, double d) { best[k] = std::min(best[k], d); });
            for (std::size_t k = 0; k < g.measures.size(); ++k)
              out.values[g.measures[k]][i] = best[k];
          }

          if (cohen.empty() && texture.empty()) continue;
          double uv[3];  // [2] unused: a 2-slot buffer draws a false -Warray-bounds (interpolate)
          interpolate(*uv_ref, ref, s.face, s.bary, s.vertex, uv);
          if (!cohen.empty()) {  // p'' = the point of B with p's UV (Eq. 2)
            const CohenResult c =
                cohen_texture_deviation(s.point, uv[0], uv[1], tgt, *uv_index, same_point, uv_hits);
            for (std::size_t m : cohen) out.values[m][i] = c.distance;
            out.cohen_case[i] = static_cast<std::uint8_t>(c.kind);
            uv_gap[i] = c.uv_gap;
          }
          if (!texture.empty()) {  // texture colours at the UVs of p and p', minimum over ties
            const Vec3 ca = sample_bilinear(*reference.texture, uv[0], uv[1]);
            const double ta[3] = {ca.x, ca.y, ca.z};
            texture_forms.transform(ta, 3, form_a, at_a);
            best.assign(texture.size(), std::numeric_limits<double>::infinity());
            for (const SurfaceHit& h : ties) {
              interpolate(*uv_tgt, tgt, h.face, h.bary, kNoFace, fb);
              const Vec3 cb = sample_bilinear(*target.texture, fb[0], fb[1]);
              const double tb[3] = {cb.x, cb.y, cb.z};
              texture_forms.transform(tb, 3, form_b, at_b);
              for (std::size_t k = 0; k < texture.size(); ++k) {
                const int f = texture_forms.form_of[k];
                best[k] = std::min(best[k],
                                   form_distance(measures[texture[k]].kind, at_a[f], at_b[f], 3));
              }
            }
            for (std::size_t k = 0; k < texture.size(); ++k) out.values[texture[k]][i] = best[k];
          }
        }
        // The batch's last ones (their ties live in `batch`: before the next one).
        int left = 0;
        for (; left + 2 <= held_count; left += 2)
          inline_deviations_pair(inline_path, held[left], held[left + 1]);
        if (left < held_count)
          for (const InlineGroup& g : inline_path) group_deviations(g, held[left]);
        from = to;
      }
    }
    out.samples_per_thread[static_cast<std::size_t>(thread)] = answered;
  }
  for (std::size_t i = 0; i < out.cohen_case.size(); ++i) {
    out.cohen_multiple += out.cohen_case[i] == static_cast<std::uint8_t>(CohenCase::kMultiple);
    out.cohen_outside += out.cohen_case[i] == static_cast<std::uint8_t>(CohenCase::kOutside);
    out.cohen_max_uv_gap = std::max(out.cohen_max_uv_gap, uv_gap[i]);
  }
  return out;
}

}  // namespace

SampleDeviations compute_deviations(const SampleSet& samples, const PreparedMesh& reference,
                                    const PreparedMesh& target, const NearestPointIndex& index,
                                    const std::vector<Measure>& measures,
                                    const DeviationOptions& options) {
  return deviations_of(StoredSamples{samples}, reference, target, index, measures, options);
}

SampleDeviations compute_deviations(const MonteCarloSamples& samples, const PreparedMesh& reference,
                                    const PreparedMesh& target, const NearestPointIndex& index,
                                    const std::vector<Measure>& measures,
                                    const DeviationOptions& options) {
  assert(&samples.mesh() == reference.mesh);
  return deviations_of(GeneratedSamples<MonteCarloSamples>{samples}, reference, target, index,
                       measures, options);
}

SampleDeviations compute_deviations(const SampleSequence& samples, const PreparedMesh& reference,
                                    const PreparedMesh& target, const NearestPointIndex& index,
                                    const std::vector<Measure>& measures,
                                    const DeviationOptions& options) {
  assert(&samples.mesh() == reference.mesh);
  return deviations_of(GeneratedSamples<SampleSequence>{samples}, reference, target, index,
                       measures, options);
}

}  // namespace meshdev
