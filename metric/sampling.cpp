#include "metric/sampling.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <sstream>

#include "metric/errors.h"
#include "metric/memory_limit.h"
#include "metric/morton_order.h"

namespace meshdev {
namespace {

// The refusal of a step that would make more than kMaxSampleCount samples. (The step in %g:
// std::to_string printed a step of 1e-300 as 0.000000.)
InvalidInput too_small(double step) {
  std::ostringstream m;
  m << "the sampling step " << step << " would create more than 2^31 samples; use a larger step";
  return InvalidInput(m.str());
}

// Monte Carlo samples made per task of MonteCarloSamples::generate_all.
constexpr std::size_t kGenerateRun = 4096;
// Grid points within 1e-9 steps of an edge count as on it (0.9 / 0.1 is 8.999999999999998).
constexpr double kGridSlack = 1e-9;

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// The hash of (seed, face) that a face's random numbers start from.
std::uint64_t face_hash(std::uint64_t seed, std::uint64_t face) {
  return splitmix64(splitmix64(seed) ^ face);
}

// Random number k of the face whose face_hash is h: a uniform double in [0, 1).
double unit_random_of(std::uint64_t h, std::uint64_t k) {
  return static_cast<double>(splitmix64(h ^ k) >> 11) * 0x1p-53;
}

// A uniform double in [0, 1) that depends only on (seed, face, k).
double unit_random(std::uint64_t seed, std::uint64_t face, std::uint64_t k) {
  return unit_random_of(face_hash(seed, face), k);
}

// Scan-conversion points of a triangle whose legs AB and AC are lab and lac long, with step Δ
// (Eq. 6): row i (s = iΔ/lab, i <= lab/Δ) holds floor((1 - s) lac / Δ) + 1 points; or limit + 1
// as soon as they are more than `limit` (a needle 1e100 long on a mesh of unit faces would
// otherwise be counted for ever: found by fuzz_nearest_point). Every operation is correctly
// rounded and monotone in Δ, so the count never grows as Δ grows (which detail::solve_scan_step
// relies on; the cap keeps that). O(min(lab / Δ, limit)).
std::size_t scan_count(double lab, double lac, double step, std::size_t limit = kMaxSampleCount) {
  const auto over = static_cast<double>(limit);
  const double rows = lab > 0.0 ? std::floor(lab / step + kGridSlack) : 0.0;
  if (!(rows <= over)) return limit + 1;
  const auto nu = static_cast<std::size_t>(rows);
  std::size_t count = 0;
  for (std::size_t i = 0; i <= nu; ++i) {
    const double s = lab > 0.0 ? static_cast<double>(i) * step / lab : 0.0;
    const double rest = 1.0 - s;
    if (rest < 0.0) break;
    const double columns = lac > 0.0 ? std::floor(rest * lac / step + kGridSlack) : 0.0;
    if (!(columns <= over)) return limit + 1;
    count += static_cast<std::size_t>(columns) + 1;
    if (count > limit) return limit + 1;
  }
  return count;
}

// Calls fn(s, t) for every scan-conversion point of triangle (a,b,c): barycentric weights s on
// b and t on c (point = a + s·AB + t·AC). Row i runs along AC at s = iΔ/|AB|.
template <class Fn>
void for_each_scan_point(const Vec3& a, const Vec3& b, const Vec3& c, double step, Fn&& fn) {
  const double lab = norm(b - a), lac = norm(c - a);
  const std::size_t nu =
      lab > 0.0 ? static_cast<std::size_t>(std::floor(lab / step + kGridSlack)) : 0;
  for (std::size_t i = 0; i <= nu; ++i) {
    const double s = lab > 0.0 ? static_cast<double>(i) * step / lab : 0.0;
    const double rest = 1.0 - s;
    if (rest < 0.0) break;
    const std::size_t nv =
        lac > 0.0 ? static_cast<std::size_t>(std::floor(rest * lac / step + kGridSlack)) : 0;
    for (std::size_t j = 0; j <= nv; ++j) {
      const double t = lac > 0.0 ? static_cast<double>(j) * step / lac : 0.0;
      fn(s, std::min(t, rest));
    }
  }
}

// The legs |AB| and |AC| of every face (what scan_count reads), on the team.
struct Legs {
  double ab, ac;
};
std::vector<Legs> face_legs(const TriMesh& m, int threads) {
  std::vector<Legs> legs(m.faces.size());
  const auto faces = static_cast<std::int64_t>(m.faces.size());
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t f = 0; f < faces; ++f) {
    const Triangle& t = m.faces[f];
    legs[f] = {norm(m.positions[t[1]] - m.positions[t[0]]),
               norm(m.positions[t[2]] - m.positions[t[0]])};
  }
  return legs;
}

// Scan-conversion points of the faces listed in `faces` (all faces if null, n of them) with
// step Δ, each face's count also written to counts[k] if counts is not null; or limit + 1 once a
// thread's share passes `limit` (the rest is skipped, so a step far too small is refused
// quickly; counts are then incomplete; a face's own count stops at limit + 1). Faces in
// parallel; an integer sum, so the result does not depend on the thread count. O(n · rows).
std::size_t scan_total(const std::vector<Legs>& legs, const std::uint32_t* faces, std::size_t n,
                       double step, int threads, std::uint32_t* counts = nullptr,
                       std::size_t limit = kMaxSampleCount) {
  assert(limit <= kMaxSampleCount);  // counts fit 32 bits
  std::atomic<bool> over{false};
  std::size_t total = 0;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1024) reduction(+ : total)
  for (std::int64_t k = 0; k < static_cast<std::int64_t>(n); ++k) {
    if (over.load(std::memory_order_relaxed)) continue;
    const Legs& l = legs[faces ? faces[k] : static_cast<std::size_t>(k)];
    const std::size_t c = scan_count(l.ab, l.ac, step, limit);
    if (counts) counts[k] = static_cast<std::uint32_t>(c);
    total += c;
    if (total > limit) over.store(true, std::memory_order_relaxed);  // this thread's share
  }
  return over.load() ? limit + 1 : total;
}

std::size_t scan_total(const TriMesh& m, double step, int threads) {
  return scan_total(face_legs(m, threads), nullptr, m.faces.size(), step, threads);
}

// The order of points point_of(0 .. n - 1) along a Morton curve over the box of the mesh's
// vertices, by morton_order's rule (the codes cut to the 24 bits from the highest in which the
// least and the greatest differ, sorted stably: points of one cell keep index order), made on the
// team for a whole mesh instead of a chunk. The codes are computed on the team; the sort is an LSD
// radix sort of two 12-bit passes, each thread counting and scattering its own contiguous range
// (stable, so the same order for any team). O(n) time, 16 bytes per point of scratch.
template <class PointOf>
std::vector<std::uint32_t> along_curve(const TriMesh& m, std::size_t n, PointOf point_of,
                                       int threads) {
  assert(n < (std::size_t{1} << 32));
  std::vector<std::uint32_t> order(n);
  const MortonGrid grid(position_bounding_box(m, threads));
  // A thread per kPointsPerThread points at most. The face order's time on a team of 1 over its
  // time on a team of 2 (a throwaway driver, one process, 40 alternating rounds, best of 5 calls
  // each; sampling_bench's BM_FaceVisitOrder shows the same): icosphere of 5,120 faces 0.78,
  // 20,480 faces 1.04, 81,920 faces 1.48; shuffled grid of 20,000 faces 1.45.
  constexpr std::size_t kPointsPerThread = 8192;
  const int team = static_cast<int>(std::clamp<std::size_t>(
      n / kPointsPerThread, 1,
      static_cast<std::size_t>(threads > 0 ? threads : omp_get_max_threads())));
  if (n < 2 || !grid.valid()) {
    for (std::uint32_t i = 0; i < n; ++i) order[i] = i;
    return order;
  }
  std::unique_ptr<std::uint64_t[]> keys(new std::uint64_t[2 * n]);  // codes, then two buffers
  std::uint64_t least = ~std::uint64_t{0}, most = 0;
#pragma omp parallel for num_threads(team) reduction(min : least) reduction(max : most)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); ++i) {
    const std::uint64_t c = grid.code(point_of(static_cast<std::size_t>(i)));
    keys[i] = c;
    least = std::min(least, c);
    most = std::max(most, c);
  }
  constexpr int kPassBits = 12, kBits = 2 * kPassBits;
  static_assert(kBits == kMortonSortBits, "the bits morton_order sorts by");
  constexpr std::size_t kBins = std::size_t{1} << kPassBits;
  const int top = least == most ? 0 : 63 - __builtin_clzll(least ^ most);
  const int low = std::max(0, top - (kBits - 1));
  constexpr std::uint64_t kMask = (std::uint64_t{1} << kBits) - 1;
  std::uint64_t* from = keys.get();
  std::uint64_t* to = keys.get() + n;
  std::vector<std::size_t> start(static_cast<std::size_t>(team) * kBins);
#pragma omp parallel num_threads(team)
  {
    const auto me = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t size = static_cast<std::size_t>(omp_get_num_threads());
    const std::size_t begin = n * me / size, end = n * (me + 1) / size;
    for (std::size_t i = begin; i < end; ++i) from[i] = (from[i] >> low & kMask) << 32 | i;
    for (int shift = 32; shift < 32 + kBits; shift += kPassBits) {
      std::size_t* mine = start.data() + me * kBins;
      std::fill(mine, mine + kBins, std::size_t{0});
      for (std::size_t i = begin; i < end; ++i) ++mine[from[i] >> shift & (kBins - 1)];
#pragma omp barrier
#pragma omp single
      {  // each bin's slots, thread by thread: the threads' ranges keep their order (stable)
        std::size_t next = 0;
        for (std::size_t b = 0; b < kBins; ++b)
          for (std::size_t t = 0; t < size; ++t) {
            const std::size_t count = start[t * kBins + b];
            start[t * kBins + b] = next;
            next += count;
          }
      }  // (the implied barrier)
      for (std::size_t i = begin; i < end; ++i)
        to[mine[from[i] >> shift & (kBins - 1)]++] = from[i];
#pragma omp barrier
#pragma omp single
      std::swap(from, to);
    }
    for (std::size_t i = begin; i < end; ++i) order[i] = static_cast<std::uint32_t>(from[i]);
  }
  return order;
}

}  // namespace

namespace detail {

std::vector<std::uint32_t> face_visit_order(const TriMesh& m, int threads) {
  // The corners of the face 16 ahead are prefetched: on a mesh stored in no spatial order they
  // lie anywhere (torus1m_shuffled.ply, 2 threads: 44 -> 28-31 ms; sampling_bench's 1.3M
  // shuffled faces on 1 thread 176 -> 120 ms; buildings.ply unchanged, 7-8 ms).
  return along_curve(
      m, m.faces.size(),
      [&m](std::size_t f) {
        if (f + 16 < m.faces.size())
          for (const std::uint32_t v : m.faces[f + 16]) __builtin_prefetch(&m.positions[v]);
        const Triangle& t = m.faces[f];
        return (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) * (1.0 / 3.0);
      },
      threads);
}

std::vector<std::uint32_t> vertex_visit_order(const TriMesh& m, int threads) {
  return along_curve(
      m, m.positions.size(), [&m](std::size_t v) { return m.positions[v]; }, threads);
}

double solve_scan_step(const TriMesh& m, std::size_t target, int threads, bool settle) {
  const std::vector<Legs> legs = face_legs(m, threads);
  const std::size_t faces = legs.size();
  double sum = 0.0;
  for (const Legs& l : legs) sum += 0.5 * l.ab * l.ac;
  if (!(sum > 0.0)) return 1.0;  // every face degenerate: each gets its corner only
  // Settled faces: each face's count never grows with Δ (scan_count), so a face with the same
  // count at lo and at hi has that count at every Δ between them, and the bisection, which only
  // narrows [lo, hi], need not count it again. `active` lists the others, with their counts at lo
  // and hi; `settled` sums the rest. The totals, hence every decision and the Δ found, are those
  // of counting every face at every step (settle = false; the tests compare the two).
  settle = settle && faces <= std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> at_lo(settle ? faces : 0), at_hi(at_lo.size()), at_mid, active;
  // Totals are counted up to `limit` only: far above the target, beyond any total between the
  // first bracket's ends on a mesh of ordinary faces (16 times the target from the area term, at
  // most about as much again from the rows' ends, and a corner per face), so the search takes
  // the same steps as counting them in full; a needle far longer than the other faces, whose
  // count at the bracket's ends is out of proportion with its area, is not counted to the end.
  const std::size_t limit = std::min<std::size_t>(
      kMaxSampleCount, 64 * std::min(target, kMaxSampleCount) + 4 * faces + 1024);
  auto total = [&](double step, std::vector<std::uint32_t>& counts) {
    return scan_total(legs, nullptr, faces, step, threads, settle ? counts.data() : nullptr, limit);
  };
  double guess = std::sqrt(sum / static_cast<double>(target));
  double lo = guess / 4, hi = guess * 4;
  std::size_t n_lo, n_hi;  // the totals at the final lo and hi, whose counts the arrays hold
  while ((n_lo = total(lo, at_lo)) < target && lo > guess * 1e-6) lo /= 4;
  while ((n_hi = total(hi, at_hi)) > target && hi < guess * 1e6) hi *= 4;
  // Counts past the limit are incomplete: count every face at every step then.
  if (n_lo > limit || n_hi > limit) settle = false;
  std::size_t settled = 0;
  if (settle) {
    active.resize(faces);
    for (std::size_t f = 0; f < faces; ++f) active[f] = static_cast<std::uint32_t>(f);
  }
  auto keep_unsettled = [&] {
    std::size_t kept = 0;
    for (std::size_t k = 0; k < active.size(); ++k) {
      assert(at_lo[k] >= at_hi[k]);
      if (at_lo[k] == at_hi[k]) {
        settled += at_lo[k];
        continue;
      }
      active[kept] = active[k];
      at_lo[kept] = at_lo[k];
      at_hi[kept] = at_hi[k];
      ++kept;
    }
    active.resize(kept);
    at_lo.resize(kept);
    at_hi.resize(kept);
  };
  if (settle) keep_unsettled();

  double best = guess;
  double best_err = 1e300;
  bool best_counted = false;  // whether the best step's total was within the limit
  for (int it = 0; it < 60; ++it) {
    const double mid = std::sqrt(lo * hi);
    std::size_t n;
    if (settle) {
      at_mid.resize(active.size());
      n = settled +
          scan_total(legs, active.data(), active.size(), mid, threads, at_mid.data(), limit);
      assert(n <= limit);  // between the totals at hi and lo, both within the limit
    } else {
      n = total(mid, at_mid);
    }
    const double err = std::fabs(static_cast<double>(n) - static_cast<double>(target));
    if (err < best_err) {  // a count within the limit is nearer than any past it
      best_err = err;
      best = mid;
      best_counted = n <= limit;
    }
    if (err <= 0.002 * static_cast<double>(target)) break;
    (n > target ? lo : hi) = mid;
    if (settle) {
      (n > target ? at_lo : at_hi).swap(at_mid);
      keep_unsettled();
    }
  }
  if (!best_counted)
    throw InvalidInput("no scan-conversion step gives about " + std::to_string(target) +
                       " face samples on this mesh: every step tried gives more than " +
                       std::to_string(limit) +
                       " (faces of very different sizes, e.g. a needle far longer than the "
                       "others); give the step, or sample by Monte Carlo");
  return best;
}

}  // namespace detail

namespace {

std::string with_commas(std::size_t n) {
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3)
    s.insert(static_cast<std::size_t>(i), ",");
  return s;
}

// SampleSet::description of a set with these counts, sampled as `o` says with step Δ.
std::string describe(std::size_t vertex_count, std::size_t edge_count, std::size_t face_count,
                     const SamplingOptions& o, double step) {
  std::ostringstream d;
  const char* sep = "";
  if (vertex_count > 0 || o.vertices) {
    d << with_commas(vertex_count) << " vertices";
    sep = " + ";
  }
  if (o.edges) {
    d << sep << with_commas(edge_count) << " edge points";
    sep = " + ";
  }
  if (o.faces == FaceSampling::kScanConversion)
    d << sep << with_commas(face_count) << " face points (scan conversion, step " << step << ")";
  if (o.faces == FaceSampling::kMonteCarlo)
    d << sep << with_commas(face_count) << " face points (Monte Carlo, seed " << o.seed << ")";
  return d.str();
}

// Every sample of `source` (a MonteCarloSamples or a SampleSequence) into out[0, size()), runs of
// kGenerateRun on `threads` (0 = OpenMP's default): each run placed by the thread that makes it.
template <class Source>
void generate_in_runs(const Source& source, Sample* out, int threads) {
  const std::size_t n = source.size();
  const auto runs = static_cast<std::int64_t>((n + kGenerateRun - 1) / kGenerateRun);
#pragma omp parallel for num_threads(threads > 0 ? threads : omp_get_max_threads()) \
    schedule(dynamic, 1)
  for (std::int64_t r = 0; r < runs; ++r) {
    const std::size_t begin = static_cast<std::size_t>(r) * kGenerateRun;
    source.generate(begin, std::min(kGenerateRun, n - begin), out + begin);
  }
}

// The first face (lowest index) using each vertex (kNoFace: none), and the vertex's corner in it.
struct FirstFaces {
  std::vector<std::uint32_t> face;
  std::vector<std::uint8_t> corner;
};
FirstFaces first_faces(const TriMesh& m) {
  FirstFaces first{std::vector<std::uint32_t>(m.positions.size(), kNoFace),
                   std::vector<std::uint8_t>(m.positions.size(), 0)};
  for (std::uint32_t f = 0; f < m.faces.size(); ++f)
    for (std::uint8_t c = 0; c < 3; ++c) {
      const std::uint32_t v = m.faces[f][c];
      if (first.face[v] == kNoFace) {
        first.face[v] = f;
        first.corner[v] = c;
      }
    }
  return first;
}

// The sample of vertex v, which sits in corner `corner` of face `face`.
Sample vertex_sample(const TriMesh& m, std::uint32_t v, std::uint32_t face, std::uint8_t corner) {
  Sample s;
  s.point = m.positions[v];
  s.vertex = v;
  s.face = face;
  s.bary = {0, 0, 0};
  s.bary[corner] = 1.0;
  s.kind = SampleKind::kVertex;
  return s;
}

void add_vertex_samples(const TriMesh& m, int threads, SampleSet& set) {
  const FirstFaces first = first_faces(m);
  const bool point_cloud = m.faces.empty();
  for (const std::uint32_t v : detail::vertex_visit_order(m, threads)) {
    if (!point_cloud && first.face[v] == kNoFace) continue;  // unreferenced
    set.samples.push_back(vertex_sample(m, v, first.face[v], first.corner[v]));
    ++set.vertex_count;
  }
}

// A mesh edge once (the corners' vertices in increasing order) with one face that has it and
// the corners of that face it joins.
struct Edge {
  std::uint32_t lo, hi, face;
  std::uint8_t c_lo, c_hi;
};

// Every distinct edge of the mesh's faces, in vertex order; zero-length index pairs (a face
// naming one vertex twice) are left out. O(F log F).
std::vector<Edge> unique_edges(const TriMesh& m) {
  std::vector<Edge> edges;
  edges.reserve(3 * m.faces.size());
  for (std::uint32_t f = 0; f < m.faces.size(); ++f)
    for (std::uint8_t c = 0; c < 3; ++c) {
      const std::uint8_t d = static_cast<std::uint8_t>((c + 1) % 3);
      std::uint32_t u = m.faces[f][c], v = m.faces[f][d];
      if (u == v) continue;
      edges.push_back(u < v ? Edge{u, v, f, c, d} : Edge{v, u, f, d, c});
    }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
    return std::tie(x.lo, x.hi, x.face) < std::tie(y.lo, y.hi, y.face);
  });
  edges.erase(
      std::unique(edges.begin(), edges.end(),
                  [](const Edge& x, const Edge& y) { return x.lo == y.lo && x.hi == y.hi; }),
      edges.end());
  return edges;
}

// Points on an edge `len` long with step Δ: round(len / Δ), at least 1; or kMaxSampleCount + 1
// where that is more than kMaxSampleCount or not a number (llround of a huge or NaN ratio is
// undefined).
std::size_t edge_point_count(double len, double step) {
  const double ratio = len / step;
  if (!(ratio < static_cast<double>(kMaxSampleCount))) return kMaxSampleCount + 1;
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(ratio)));
}

// How many edge samples `edges` (unique_edges) get with step Δ; throws InvalidInput (too_small)
// once they are more than kMaxSampleCount, before any is made (an edge 1e100 long with a unit step
// made samples until memory ran out). O(E).
std::size_t edge_total(const TriMesh& m, const std::vector<Edge>& edges, double step) {
  std::size_t total = 0;
  for (const Edge& e : edges) {
    total += edge_point_count(norm(m.positions[e.hi] - m.positions[e.lo]), step);
    if (total > kMaxSampleCount) throw too_small(step);
  }
  return total;
}

// The edge samples of `edges` with step Δ. Precondition: edge_total(m, edges, step) succeeded.
void add_edge_samples(const TriMesh& m, const std::vector<Edge>& edges, double step,
                      SampleSet& set) {
  for (const Edge& e : edges) {
    const Vec3& p = m.positions[e.lo];
    const Vec3& q = m.positions[e.hi];
    const double len = norm(q - p);
    const std::size_t n = edge_point_count(len, step);
    for (std::size_t k = 0; k < n; ++k) {
      const double t = (static_cast<double>(k) + 0.5) / static_cast<double>(n);
      Sample s;
      s.point = (1.0 - t) * p + t * q;
      s.face = e.face;
      s.bary = {0, 0, 0};
      s.bary[e.c_lo] = 1.0 - t;
      s.bary[e.c_hi] = t;
      s.weight = len / static_cast<double>(n);
      s.kind = SampleKind::kEdge;
      set.samples.push_back(s);
      ++set.edge_count;
    }
  }
}

// Face samples, faces in parallel in the visit order: count(f) samples per face, then
// fill(f, out, n) places face f's n samples in its own slots (raw storage: see SampleAllocator),
// so the set is the same as a serial pass for any thread count and each slot is first written by
// the thread that fills it.
template <class Count, class Fill>
void add_face_samples(const TriMesh& m, int threads, SampleSet& set, Count&& count, Fill&& fill) {
  const auto faces = static_cast<std::int64_t>(m.faces.size());
  const std::vector<std::uint32_t> order = detail::face_visit_order(m, threads);
  std::vector<std::size_t> first(m.faces.size() + 1);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t k = 0; k < faces; ++k) first[k + 1] = count(order[k]);
  first[0] = set.samples.size();
  for (std::size_t k = 0; k < m.faces.size(); ++k) first[k + 1] += first[k];
  set.samples.resize(first.back());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 256)
  for (std::int64_t k = 0; k < faces; ++k)
    fill(order[k], set.samples.data() + first[k], first[k + 1] - first[k]);
  set.face_count += first.back() - first[0];
}

void add_scan_samples(const TriMesh& m, double step, int threads, SampleSet& set) {
  auto corners = [&](std::uint32_t f) {
    const Triangle& t = m.faces[f];
    return std::array<const Vec3*, 3>{&m.positions[t[0]], &m.positions[t[1]], &m.positions[t[2]]};
  };
  add_face_samples(
      m, threads, set,
      [&](std::uint32_t f) {
        const auto v = corners(f);
        return scan_conversion_count(*v[0], *v[1], *v[2], step);
      },
      [&](std::uint32_t f, Sample* out, std::size_t n) {
        const auto v = corners(f);
        const Vec3 &a = *v[0], &b = *v[1], &c = *v[2];
        const double w = face_area(m, f) / static_cast<double>(n);
        std::size_t k = 0;
        for_each_scan_point(a, b, c, step, [&](double s, double t) {
          assert(k < n);
          ::new (static_cast<void*>(out + k++)) Sample{
              a + s * (b - a) + t * (c - a), f, kNoFace, {1.0 - s - t, s, t}, w, SampleKind::kFace};
        });
        assert(k == n);
      });
}

}  // namespace

const char* sample_kind_name(SampleKind k) {
  switch (k) {
    case SampleKind::kVertex:
      return "vertex";
    case SampleKind::kEdge:
      return "edge";
    case SampleKind::kFace:
      return "face";
  }
  return "?";
}

std::size_t scan_conversion_count(const Vec3& a, const Vec3& b, const Vec3& c, double step) {
  return scan_count(norm(b - a), norm(c - a), step);
}

namespace {

// The errors sample_surface raises for `o` on `mesh` before it samples anything.
void check_options(const TriMesh& mesh, const SamplingOptions& o) {
  const bool wants_faces = o.faces != FaceSampling::kNone;
  if ((wants_faces || o.edges) && mesh.faces.empty())
    throw InvalidInput(
        "cannot sample faces or edges of a mesh without faces (a point cloud); "
        "sample its vertices only");
  check_sampling_options(o);
}

std::size_t face_target(const TriMesh& mesh, const SamplingOptions& o) {
  return o.target_count > 0 ? o.target_count : 10 * mesh.faces.size();
}

}  // namespace

void check_sampling_options(const SamplingOptions& o) {
  if (o.step < 0.0 || o.step_fraction < 0.0 || !std::isfinite(o.step) ||
      !std::isfinite(o.step_fraction))
    throw InvalidInput("the sampling step must be a positive finite number");
  if (o.target_count > kMaxSampleCount)  // Monte Carlo allocated them and ran out of memory
    throw InvalidInput("a target of " + with_commas(o.target_count) +
                       " face samples is more than the 2^31 (2,147,483,648) a sample set holds");
}

bool monte_carlo_only(const SamplingOptions& o) {
  return o.faces == FaceSampling::kMonteCarlo && !o.vertices && !o.edges;
}

MonteCarloSamples monte_carlo_samples(const TriMesh& mesh, const SamplingOptions& o) {
  assert(monte_carlo_only(o));
  check_options(mesh, o);
  return MonteCarloSamples(mesh, face_target(mesh, o), o.seed,
                           o.threads > 0 ? o.threads : omp_get_max_threads());
}

SampleSet sample_surface(const TriMesh& mesh, const SamplingOptions& o, double diagonal) {
  check_options(mesh, o);

  SampleSet set;
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  const std::size_t target = face_target(mesh, o);
  double step = o.step > 0.0 ? o.step : o.step_fraction * diagonal;
  const bool needs_step = o.faces == FaceSampling::kScanConversion || o.edges;
  if (needs_step && !(step > 0.0)) {
    if (o.step > 0.0 || o.step_fraction > 0.0)
      throw InvalidInput("the sampling step is 0 (is the mesh's bounding box a single point?)");
    if (o.faces == FaceSampling::kScanConversion || o.faces == FaceSampling::kMonteCarlo) {
      step = detail::solve_scan_step(mesh, target, threads);
    } else {  // edges alone: spread the target count over the total edge length
      double length = 0.0;
      for (const Triangle& t : mesh.faces)
        for (int c = 0; c < 3; ++c)
          length += norm(mesh.positions[t[(c + 1) % 3]] - mesh.positions[t[c]]);
      step = length > 0.0 ? 0.5 * length / static_cast<double>(target) : 1.0;
    }
  }
  const std::size_t scan_count =
      o.faces == FaceSampling::kScanConversion ? scan_total(mesh, step, threads) : 0;
  if (scan_count > kMaxSampleCount) throw too_small(step);
  const std::vector<Edge> edges = o.edges ? unique_edges(mesh) : std::vector<Edge>{};
  const std::size_t edge_count = o.edges ? edge_total(mesh, edges, step) : 0;
  set.step = needs_step ? step : 0.0;
  // Room for every vertex, edge and face sample at once (Monte Carlo makes at most target +
  // faces), so the set is not copied as it grows.
  const std::size_t expected =
      (o.vertices ? mesh.positions.size() : 0) + edge_count + scan_count +
      (o.faces == FaceSampling::kMonteCarlo ? target + mesh.faces.size() : 0);
  check_fits_in_memory(static_cast<double>(expected) * sizeof(Sample),
                       with_commas(expected) + " samples",
                       "use fewer samples or a larger sampling step");
  if (expected <= kMaxSampleCount) set.samples.reserve(expected);

  if (o.vertices) add_vertex_samples(mesh, threads, set);
  if (o.edges) add_edge_samples(mesh, edges, step, set);
  if (o.faces == FaceSampling::kScanConversion) add_scan_samples(mesh, step, threads, set);
  if (o.faces == FaceSampling::kMonteCarlo) {
    const MonteCarloSamples mc(mesh, target, o.seed, threads);
    const std::size_t offset = set.samples.size();
    set.samples.resize(offset + mc.size());  // raw storage: each sample placed by its thread
    mc.generate_all(set.samples.data() + offset, threads);
    set.face_count += mc.size();
  }

  // Weights: face samples carry area; with face samples present, vertex and edge samples only
  // hunt the maximum (weight 0); edge samples carry length when they are the finest kind.
  // Vertex and edge samples come first: the face samples (which keep their weights) are not read.
  assert(set.vertex_count + set.edge_count + set.face_count == set.samples.size());
  for (std::size_t i = 0; i < set.vertex_count + set.edge_count; ++i) {
    Sample& s = set.samples[i];
    assert(s.kind != SampleKind::kFace);
    if (set.face_count > 0)
      s.weight = 0.0;
    else if (s.kind == SampleKind::kVertex)
      s.weight = set.edge_count > 0 ? 0.0 : 1.0;
  }
  const bool one_kind = (set.vertex_count > 0) + (set.edge_count > 0) + (set.face_count > 0) == 1;
  if (one_kind && (set.vertex_count > 0 || o.faces == FaceSampling::kMonteCarlo))
    set.equal_weight = set.samples.front().weight;  // vertices weigh 1; Monte Carlo area / count

  set.description = describe(set.vertex_count, set.edge_count, set.face_count, o, step);
  return set;
}

MonteCarloSamples::MonteCarloSamples(const TriMesh& mesh, std::size_t target, std::uint64_t seed,
                                     int threads)
    : mesh_(&mesh), seed_(seed), first_(mesh.faces.size() + 1, 0) {
  const auto faces = static_cast<std::int64_t>(mesh.faces.size());
  const int team = threads > 0 ? threads : omp_get_max_threads();
  // The faces' areas on the team, each kept in its face's slot of first_ (a double's bits), then
  // summed in face order: surface_area's total, bit for bit, and the counts below read the areas
  // instead of computing them again (buildings.ply, 400k faces: 1.3 ms serial saved).
  static_assert(sizeof(double) == sizeof(std::size_t), "an area is kept in an offset's slot");
  auto area_at = [this](std::size_t f) {
    double a;
    std::memcpy(&a, &first_[f + 1], sizeof a);
    return a;
  };
#pragma omp parallel for num_threads(team) schedule(static)
  for (std::int64_t f = 0; f < faces; ++f) {
    const double a = face_area(mesh, static_cast<std::size_t>(f));
    std::memcpy(&first_[f + 1], &a, sizeof a);
  }
  double total = 0.0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) total += area_at(f);
  assert(faces == 0 || total == surface_area(mesh));
  // Faces wider than about 1e77 overflow their area (its squared cross product), and the counts
  // below would be inf / inf (found by fuzz_nearest_point).
  if (std::isinf(total))
    throw InvalidInput(
        "Monte Carlo sampling needs a finite surface area, and this mesh's overflows double "
        "(faces wider than about 1e77): scale the mesh, or sample by scan conversion");
  if (!(total > 0.0) || target == 0) {
    std::fill(first_.begin(), first_.end(), 0);
    return;
  }
  weight_ = total / static_cast<double>(target);
  // Each face's count (in its own slot), then the offsets in the visit order.
  order_ = detail::face_visit_order(mesh, team);
  std::vector<std::size_t> first(mesh.faces.size() + 1, 0);
#pragma omp parallel for num_threads(team) schedule(static)
  for (std::int64_t k = 0; k < faces; ++k) {
    const std::uint32_t f = order_[k];
    const double expected = static_cast<double>(target) * area_at(f) / total;
    first[k + 1] = static_cast<std::size_t>(
        std::floor(expected + unit_random(seed, static_cast<std::uint64_t>(f), ~0ull)));
  }
  for (std::size_t k = 0; k < mesh.faces.size(); ++k) first[k + 1] += first[k];
  first_ = std::move(first);
}

void MonteCarloSamples::generate(std::size_t begin, std::size_t count, Sample* out) const {
  assert(begin + count <= size());
  // The face holding sample `begin`, the slot-th visited: the last slot with first_[slot] <=
  // begin (faces with no samples share their successor's offset, so this one has a sample).
  auto slot = static_cast<std::size_t>(std::upper_bound(first_.begin(), first_.end(), begin) -
                                       first_.begin() - 1);
  std::size_t k = begin - first_[slot];
  for (std::size_t j = 0; j < count;) {
    while (first_[slot] + k == first_[slot + 1]) {  // past this face's samples
      ++slot;
      k = 0;
    }
    // The face's samples k .. of this range: its corners and hash read once.
    const std::uint32_t face = order_[slot];
    const Triangle& tri = mesh_->faces[face];
    const Vec3 &a = mesh_->positions[tri[0]], &b = mesh_->positions[tri[1]],
               &c = mesh_->positions[tri[2]];
    const std::uint64_t h = face_hash(seed_, face);
    for (const std::size_t end = std::min(first_[slot + 1] - first_[slot], k + count - j); k < end;
         ++k, ++j) {
      const double r = std::sqrt(unit_random_of(h, 2 * k));
      const double r2 = unit_random_of(h, 2 * k + 1);
      const std::array<double, 3> bary{1.0 - r, r * (1.0 - r2), r * r2};
      ::new (static_cast<void*>(out + j)) Sample{
          bary[0] * a + bary[1] * b + bary[2] * c, face, kNoFace, bary, weight_, SampleKind::kFace};
    }
  }
}

void MonteCarloSamples::generate_all(Sample* out, int threads) const {
  generate_in_runs(*this, out, threads);
}

Sample MonteCarloSamples::at(std::size_t i) const {
  Sample s;
  generate(i, 1, &s);
  return s;
}

std::string MonteCarloSamples::description() const {
  std::ostringstream d;
  d << with_commas(size()) << " face points (Monte Carlo, seed " << seed_ << ")";
  return d.str();
}

SampleSequence::SampleSequence(const TriMesh& mesh, const SamplingOptions& o, double diagonal)
    : mesh_(&mesh) {
  assert(sequence_sampling(o));
  check_options(mesh, o);
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  const std::size_t target = face_target(mesh, o);
  // The step and the errors of sample_surface, in its order.
  double step = o.step > 0.0 ? o.step : o.step_fraction * diagonal;
  if (o.faces == FaceSampling::kScanConversion) {
    if (!(step > 0.0)) {
      if (o.step > 0.0 || o.step_fraction > 0.0)
        throw InvalidInput("the sampling step is 0 (is the mesh's bounding box a single point?)");
      step = detail::solve_scan_step(mesh, target, threads);
    }
    // Each face's count in the visit order, then their offsets; a step far too small is refused
    // as quickly as sample_surface refuses it.
    order_ = detail::face_visit_order(mesh, threads);
    std::vector<std::uint32_t> counts(mesh.faces.size());
    if (scan_total(face_legs(mesh, threads), order_.data(), order_.size(), step, threads,
                   counts.data()) > kMaxSampleCount)
      throw too_small(step);
    first_.resize(mesh.faces.size() + 1);
    first_[0] = 0;
    for (std::size_t k = 0; k < mesh.faces.size(); ++k) first_[k + 1] = first_[k] + counts[k];
    face_count_ = first_.back();
    step_ = step;
  }
  if (o.vertices) {
    const FirstFaces first = first_faces(mesh);
    const bool point_cloud = mesh.faces.empty();
    for (const std::uint32_t v : detail::vertex_visit_order(mesh, threads))
      if (point_cloud || first.face[v] != kNoFace)
        vertices_.push_back({v, first.face[v], first.corner[v]});
  }
  if (o.faces == FaceSampling::kMonteCarlo) {
    monte_carlo_.emplace(mesh, target, o.seed, threads);
    face_count_ = monte_carlo_->size();
  }
  // sample_surface's weights: with face samples, vertex samples only hunt the maximum.
  vertex_weight_ = face_count_ > 0 ? 0.0 : 1.0;
  if (vertices_.empty() != (face_count_ == 0) && (!vertices_.empty() || monte_carlo_))
    equal_weight_ = vertices_.empty() ? monte_carlo_->weight() : vertex_weight_;
  description_ = describe(vertices_.size(), 0, face_count_, o, step);
}

void SampleSequence::generate(std::size_t begin, std::size_t count, Sample* out) const {
  assert(begin + count <= size());
  std::size_t j = 0;
  for (; j < count && begin + j < vertices_.size(); ++j) {
    const VertexRef& v = vertices_[begin + j];
    ::new (static_cast<void*>(out + j)) Sample(vertex_sample(*mesh_, v.vertex, v.face, v.corner));
    out[j].weight = vertex_weight_;
  }
  if (j == count) return;
  const std::size_t from = begin + j - vertices_.size();
  if (monte_carlo_)
    monte_carlo_->generate(from, count - j, out + j);
  else
    generate_scan(from, count - j, out + j);
}

// Face samples [begin, begin + count) of the scan conversion: add_scan_samples' points, weights
// and order (for_each_scan_point, entered at the range's first point; the tests compare the two).
void SampleSequence::generate_scan(std::size_t begin, std::size_t count, Sample* out) const {
  assert(begin + count <= face_count_);
  // The slot-th visited face holds sample `begin` (as in MonteCarloSamples::generate).
  auto slot = static_cast<std::size_t>(std::upper_bound(first_.begin(), first_.end(), begin) -
                                       first_.begin() - 1);
  std::size_t k = begin - first_[slot];  // the point of the face to place next
  for (std::size_t j = 0; j < count;) {
    while (first_[slot] + k == first_[slot + 1]) {
      ++slot;
      k = 0;
    }
    const std::uint32_t face = order_[slot];
    const Triangle& tri = mesh_->faces[face];
    const Vec3 &a = mesh_->positions[tri[0]], &b = mesh_->positions[tri[1]],
               &c = mesh_->positions[tri[2]];
    const double w = face_area(*mesh_, face) / static_cast<double>(first_[slot + 1] - first_[slot]);
    const double lab = norm(b - a), lac = norm(c - a);
    const std::size_t nu =
        lab > 0.0 ? static_cast<std::size_t>(std::floor(lab / step_ + kGridSlack)) : 0;
    std::size_t row_first =
        0;  // the face's point that starts row i (k >= it: rows before k skipped)
    for (std::size_t i = 0; i <= nu && j < count; ++i) {
      const double s = lab > 0.0 ? static_cast<double>(i) * step_ / lab : 0.0;
      const double rest = 1.0 - s;
      if (rest < 0.0) break;
      const std::size_t nv =
          lac > 0.0 ? static_cast<std::size_t>(std::floor(rest * lac / step_ + kGridSlack)) : 0;
      const std::size_t row_end = row_first + nv + 1;
      for (std::size_t col = k - row_first; k < row_end && j < count; ++col, ++k, ++j) {
        const double t = std::min(lac > 0.0 ? static_cast<double>(col) * step_ / lac : 0.0, rest);
        ::new (static_cast<void*>(out + j))
            Sample{a + s * (b - a) + t * (c - a), face, kNoFace,
                   {1.0 - s - t, s, t},           w,    SampleKind::kFace};
      }
      row_first = row_end;
    }
    assert(j == count || k == first_[slot + 1] - first_[slot]);
  }
}

void SampleSequence::generate_all(Sample* out, int threads) const {
  generate_in_runs(*this, out, threads);
}

Sample SampleSequence::at(std::size_t i) const {
  Sample s;
  generate(i, 1, &s);
  return s;
}

void SampleSequence::weights(double* out, int threads) const {
  const int team = threads > 0 ? threads : omp_get_max_threads();
  const std::size_t nv = vertices_.size();
  std::fill(out, out + nv, vertex_weight_);
  if (monte_carlo_) {
    std::fill(out + nv, out + nv + face_count_, monte_carlo_->weight());
    return;
  }
  const auto faces = static_cast<std::int64_t>(first_.empty() ? 0 : first_.size() - 1);
#pragma omp parallel for num_threads(team) schedule(static)
  for (std::int64_t k = 0; k < faces; ++k) {
    const std::size_t n = first_[k + 1] - first_[k];
    if (n == 0) continue;
    std::fill(out + nv + first_[k], out + nv + first_[k + 1],
              face_area(*mesh_, order_[k]) / static_cast<double>(n));
  }
}

bool sequence_sampling(const SamplingOptions& o) {
  return !o.edges;
}

void set_sample_kinds(SamplingOptions& o, const std::string& list) {
  o.vertices = o.edges = false;
  o.faces = FaceSampling::kNone;
  std::stringstream in(list);
  std::string kind;
  while (std::getline(in, kind, ',')) {
    if (kind == "vertices")
      o.vertices = true;
    else if (kind == "edges")
      o.edges = true;
    else if (kind == "faces")
      o.faces = FaceSampling::kScanConversion;
    else if (kind == "montecarlo")
      o.faces = FaceSampling::kMonteCarlo;
    else if (!kind.empty())
      throw InvalidInput("unknown sample kind '" + kind +
                         "' (use vertices, edges, faces, montecarlo)");
  }
}

}  // namespace meshdev
