// peer_compare: the same samples on mesh A, the same target mesh B, in one process and one run,
// through
//   (a) meshdev: compute_deviations() with geometry + normal + "temperature" (the whole
//       per-sample unit of the metric: closest point, all equidistant ties, three measures);
//   (b) Embree 3 rtcPointQuery, given its best (the research note's setup): samples in Morton
//       order (a Hilbert order, --order hilbert, was as fast for it on 2 threads and up to 5 %
//       faster on 1: docs/performance.md §4), RTC_BUILD_QUALITY_LOW (its fast build), shared
//       float buffers, and a callback that computes the exact closest point on OUR arrays (never
//       rtcGetGeometryBufferData; in double on our double positions, or in float with
//       --embree-float), then interpolation of one 3-float vertex attribute and writes of
//       distance, face, attribute;
//   (c) CGAL 5.5 AABB tree (Epick) closest_point_and_primitive with its KD-tree accelerator, then
//       barycentrics and the same interpolation.
// For each: build time, query throughput on each thread count (best of --repeats), CPU share =
// process CPU seconds / (wall x threads), and meshdev's speed ratio over each peer. Checks that the
// three agree (mean distance, max per-sample difference). Prints a table and CSV rows.
//
// usage: peer_compare A B N [--seed S] [--order morton|hilbert|native] [--threads 1,2]
//                           [--repeats 3] [--engines meshdev,embree,cgal] [--embree-hint]
//                           [--embree-float] [--rounds R [--rounds-csv FILE]] [--csv FILE]
//                           [--label NAME] [--ab R [--ab-chunk C] [--ab-build]] [--check REL]
// --order: the order every engine gets the samples in (sorted outside the timing): morton (the
// default: the research note's setup for Embree), hilbert (a Hilbert curve on the same grid;
// meshdev puts each chunk of 1,024 back in Morton order, as it does any order) or native (the
// sampler's: face by face, the faces along a Morton curve of their centroids).
// --check REL: the agreement as a gate: the process exits 1 (after its CSV rows are written) if
// the per-sample distances of any two engines differ by more than REL times B's bounding-box
// diagonal, or an engine gave a distance that is not finite. The peers hand their distances over
// in float, so REL below about 1e-7 fails on rounding alone (a float of d is within 6e-8 d, and a
// distance of a sample on B is the square root of a rounding-size square, about 1e-8 of the
// diagonal); run_all.sh uses 1e-6. With --embree-float Embree's closest points are computed in
// float too: 3.9e-7 of the diagonal was seen (`peer_compare bunny00.off bunny00_s7k.ply 50000
// --engines meshdev,embree --embree-float --check 1e-6`), so allow 1e-5 there. A different
// nearest face differs by far more, except between faces at almost equal distances, which give
// almost equal distances anyway. Needs two engines.
// --rounds R: after the table, meshdev and Embree (and Embree+hint with --embree-hint) are timed
// once each, one after the other, on each thread count of --threads in turn, R rounds over (the
// thread counts' order reversed every other round), and the ratio of each run is printed with the
// median and range: on a shared host whose speed drifts over minutes, the best-of-N of engines
// timed minutes apart can differ by a drift that hits only one of them. Each round also gives
// meshdev's speed-up over its first thread count, from runs seconds apart, whose median over the
// rounds a drift moves far less than the ratio of two medians taken minutes apart. One untimed
// run of each engine goes first (the first touch of meshdev's result arrays). Before each
// meshdev run a probe of the host (pipes_probe: 16 chains of multiply-adds, ~15 ms) is timed on
// the same thread count, and the probe's own speed-up is printed beside meshdev's: below 2 where
// the host gave the process less than two physical cores.
// --rounds-csv FILE: each round's throughputs and ratios are also appended to FILE as CSV, one
// row per (round, thread count), for bench/peers/table_md.py's table of the rounds' medians;
// `start_s` is when the row's meshdev run began, in seconds after the first round's, and
// `probe_s` the seconds of the host probe just before it, and `thread_split` how unevenly the
// threads of meshdev's run shared its samples (thread_split below): near 1 where both cores ran
// at one speed through the run, well above where one of them was slowed during it.
// --ab R: instead of the above, meshdev alone, variant 0 against variant 1 of an experiment
// (metric/ab_variant.h): the samples are cut into chunks of C (65536), each chunk is answered by
// both variants in turn, which goes first alternating from chunk to chunk and round to round, and
// each round's ratio (variant 0's time / variant 1's: > 1 when variant 1 is faster) is printed
// with the median and range over R rounds, per thread count of --threads. Also checks that both
// variants give the same deviations and tie counts, bit for bit. --ab-build: a change to the
// build: each variant queries its own index, built under that variant; first both builds are
// timed R times over per thread count, alternating which goes first, with the median ratio.
#include <embree3/rtcore.h>
#include <malloc.h>
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "bench/peers/fp_chains.h"
#include "metric/ab_variant.h"
#include "metric/attribute_deviation.h"
#include "metric/attributes.h"
#include "metric/chunk_schedule.h"
#include "metric/io/mesh_io.h"
#include "metric/mesh.h"
#include "metric/nearest_point.h"
#include "metric/sampling.h"
#include "metric/triangle_bvh.h"

namespace {

using meshdev::Vec3;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double rss_mib() {  // current resident set
  std::ifstream in("/proc/self/statm");
  long pages = 0, resident = 0;
  in >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1048576.0;
}

// Heap bytes in use (malloc arenas + mmapped chunks): unlike the RSS, not hidden by the reuse of
// memory freed earlier in the process.
double heap_mib() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd) / 1048576.0;
}

// Memory a build added: the larger of the heap growth and the RSS growth (Embree may map its own
// pages; the RSS alone misses reused heap).
struct MemProbe {
  double heap0 = heap_mib(), rss0 = rss_mib();
  double mib() const { return std::max(heap_mib() - heap0, rss_mib() - rss0); }
};

// The process's minor page faults so far (first touches of anonymous memory, mostly).
long minor_faults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

double peak_rss_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

std::string loadavg() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

// One timed loop: wall seconds and the CPU share it got (of the best run), and the first run's
// wall seconds (on pages the process has not touched before).
struct Timing {
  double wall = 0, share = 0;
  double first = 0;
};

// The host's capacity on `threads` threads now: the seconds of 2^23 steps of sixteen independent
// chains of multiply-adds split over them (fp_chains<16>, host_probe's throughput-bound "pipes"
// kernel, about 15 ms on one thread here). Taken before each meshdev run of the rounds: the
// 1-thread time over the 2-thread one is 2 where the host gives two physical cores, about 1.4
// where it runs both vCPUs on one core's two hardware threads.
volatile double g_probe_sink = 0.0;  // the probe's sums, kept so that the work is done
double pipes_probe(int threads) {
  constexpr long kSteps = 1L << 23;
  double sum = 0.0;
  const auto t0 = Clock::now();
#pragma omp parallel num_threads(threads) reduction(+ : sum)
  sum += meshdev_bench::fp_chains<16>(kSteps / threads);
  const double seconds = seconds_since(t0);
  g_probe_sink = g_probe_sink + sum;
  return seconds;
}

// How unevenly a meshdev run's team shared its samples: the most any thread answered over the
// fewest (SampleDeviations::samples_per_thread). The threads take chunks until none is left, so
// this is the ratio of their speeds over the run: 1.01-1.06 in undisturbed 2-thread runs here
// (torus100k -> 10k, about 490 chunks each), 1.39 in one whose rate fell by a fifth without any
// pause in either thread (docs/performance-log.md §3, fifty-first session). 1 for one thread.
double thread_split(const meshdev::SampleDeviations& d) {
  if (d.samples_per_thread.empty()) return 1.0;
  const auto [lo, hi] =
      std::minmax_element(d.samples_per_thread.begin(), d.samples_per_thread.end());
  return *lo == 0 ? std::numeric_limits<double>::infinity()
                  : static_cast<double>(*hi) / static_cast<double>(*lo);
}

template <class F>
Timing time_best(int repeats, int threads, F&& run) {
  Timing best{std::numeric_limits<double>::infinity(), 0};
  for (int r = 0; r < repeats; ++r) {
    const double c0 = cpu_seconds();
    const auto t0 = Clock::now();
    run();
    const double wall = seconds_since(t0);
    const double cpu = cpu_seconds() - c0;
    if (wall < best.wall) best = {wall, cpu / (wall * threads), best.first};
    if (r == 0) best.first = wall;
  }
  return best;
}

// ---------------------------------------------------------------------------------------------
// Samples: meshdev's area-uniform Monte Carlo sampler, optionally sorted along a Morton curve.

std::uint64_t spread21(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

// The index along a 3D Hilbert curve of the cell (x, y, z) of a 2^21 grid: Skilling's transform
// of the coordinates into the curve's "transposed" form, then its bits interleaved as Morton's
// are (J. Skilling, "Programming the Hilbert curve", AIP Conf. Proc. 707, 2004). Consecutive
// indices are cells that share a face. O(21).
std::uint64_t hilbert21(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  std::uint32_t c[3] = {x, y, z};
  for (std::uint32_t q = 1u << 20; q > 1; q >>= 1) {  // undo the excess work
    const std::uint32_t low = q - 1;
    for (std::uint32_t& ci : c) {
      if ((ci & q) != 0) {
        c[0] ^= low;  // invert
      } else {
        const std::uint32_t t = (c[0] ^ ci) & low;  // exchange
        c[0] ^= t;
        ci ^= t;
      }
    }
  }
  c[1] ^= c[0];  // Gray encode
  c[2] ^= c[1];
  std::uint32_t t = 0;
  for (std::uint32_t q = 1u << 20; q > 1; q >>= 1)
    if ((c[2] & q) != 0) t ^= q - 1;
  for (std::uint32_t& ci : c) ci ^= t;
  return spread21(c[2]) | spread21(c[1]) << 1 | spread21(c[0]) << 2;
}

// How an --order is named in the printed table.
const char* order_name(const std::string& order) {
  return order == "morton" ? "Morton" : order == "hilbert" ? "Hilbert" : "native";
}

// Sorts the samples along a space-filling curve of a 2^21 grid over `box` (A's bounding box):
// Morton's (the grid compute_deviations orders its chunks on, so it finds them already sorted and
// leaves them) or, with `hilbert`, Hilbert's (which compute_deviations puts back in Morton order a
// chunk at a time, as it does any order).
void curve_sort(meshdev::SampleSet& set, const meshdev::BoundingBox& box, bool hilbert) {
  const Vec3 ext = box.max - box.min;
  const double scale = 2097151.0 / std::max({ext.x, ext.y, ext.z, 1e-300});
  auto cell = [&](double x, double x0) -> std::uint32_t {  // clamped to the grid, as there
    const double t = (x - x0) * scale;
    return t >= 0.0 ? (t < 2097151.0 ? static_cast<std::uint32_t>(t) : 2097151u) : 0u;
  };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(set.samples.size());
  for (std::size_t i = 0; i < set.samples.size(); ++i) {
    const Vec3& p = set.samples[i].point;
    const std::uint32_t x = cell(p.x, box.min.x), y = cell(p.y, box.min.y),
                        z = cell(p.z, box.min.z);
    keys[i] = {hilbert ? hilbert21(x, y, z) : spread21(x) | spread21(y) << 1 | spread21(z) << 2,
               static_cast<std::uint32_t>(i)};
  }
  std::sort(keys.begin(), keys.end());
  meshdev::SampleVector sorted;
  sorted.reserve(keys.size());
  for (const auto& key : keys) sorted.push_back(set.samples[key.second]);
  set.samples.swap(sorted);
}

// A smooth per-vertex scalar, the same function of position on both meshes (so the deviation is
// small and real), scaled by A's box so it does not depend on B.
void add_temperature(meshdev::TriMesh& m, const meshdev::BoundingBox& box) {
  const double d = std::max(box.diagonal(), 1e-300);
  auto& ch = m.add_channel("temperature", meshdev::AttributeKind::kScalar,
                           meshdev::Storage::kPerVertex, 1);
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    const Vec3 q = (m.positions[v] - box.min) * (1.0 / d);
    ch.values[v] = 20 + 10 * std::sin(6.283 * q.x) * std::cos(6.283 * q.y) + 5 * q.z;
  }
}

// ---------------------------------------------------------------------------------------------
// Closest point on a triangle (Ericson, Real-Time Collision Detection §5.1.5), templated on the
// scalar: float for Embree (its native precision), double for CGAL's barycentrics.

template <class T>
struct V3 {
  T x, y, z;
};
template <class T>
inline V3<T> sub(V3<T> a, V3<T> b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
inline T dot3(V3<T> a, V3<T> b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// Returns the squared distance; bary receives the barycentrics of the closest point.
template <class T>
inline T closest_on_triangle(V3<T> p, V3<T> a, V3<T> b, V3<T> c, T bary[3]) {
  const V3<T> ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const T d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  T u = 1, v = 0, w = 0;
  if (d1 <= 0 && d2 <= 0) {
    u = 1, v = 0, w = 0;
  } else {
    const V3<T> bp = sub(p, b);
    const T d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    const V3<T> cp = sub(p, c);
    const T d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    const T vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d3 >= 0 && d4 <= d3) {
      u = 0, v = 1, w = 0;
    } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
      const T t = d1 / (d1 - d3);
      u = 1 - t, v = t, w = 0;
    } else if (d6 >= 0 && d5 <= d6) {
      u = 0, v = 0, w = 1;
    } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
      const T t = d2 / (d2 - d6);
      u = 1 - t, v = 0, w = t;
    } else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
      const T t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      u = 0, v = 1 - t, w = t;
    } else {
      const T denom = 1 / (va + vb + vc);
      v = vb * denom, w = vc * denom, u = 1 - v - w;
    }
  }
  bary[0] = u, bary[1] = v, bary[2] = w;
  const V3<T> q{u * a.x + v * b.x + w * c.x, u * a.y + v * b.y + w * c.y,
                u * a.z + v * b.z + w * c.z};
  const V3<T> e = sub(p, q);
  return dot3(e, e);
}

// Per-sample outputs of a peer: the hot-loop unit's writes.
struct PeerOut {
  std::vector<float> distance;
  std::vector<std::uint32_t> face;
  std::vector<float> attribute;  // 3 per sample
  void resize(std::size_t n) {
    distance.assign(n, 0.f);
    face.assign(n, 0);
    attribute.assign(3 * n, 0.f);
  }
};

// ---------------------------------------------------------------------------------------------
// Embree 3.

struct EmbreeArrays {               // our own arrays, shared with Embree (no copy inside Embree)
  std::vector<float> vertices;      // 3 per vertex + 1 float of padding (Embree reads 16 bytes)
  std::vector<std::uint32_t> tris;  // 3 per face
};

EmbreeArrays embree_arrays(const meshdev::TriMesh& b) {
  EmbreeArrays arrays;
  arrays.vertices.resize(3 * b.num_vertices() + 1, 0.f);
  for (std::size_t v = 0; v < b.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) arrays.vertices[3 * v + k] = static_cast<float>(b.positions[v][k]);
  arrays.tris.resize(3 * b.num_faces());
  for (std::size_t f = 0; f < b.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) arrays.tris[3 * f + k] = b.faces[f][k];
  return arrays;
}

// T = double (default): the callback reads our double positions and the double sample, so
// slivers cannot make it pick a wrong triangle (measured: no slower than float). T = float
// (--embree-float): Embree's own precision throughout, our float copy of the positions.
template <class T>
struct EmbreeQuery {
  const T* v;
  const std::uint32_t* t;
  V3<T> p;  // the sample, in T (Embree's RTCPointQuery holds it in float)
  T best = std::numeric_limits<T>::infinity();  // squared distance
  std::uint32_t face = 0;
  T bary[3] = {1, 0, 0};
};

template <class T>
inline V3<T> vertex(const T* v, std::uint32_t i) {
  return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
}

template <class T>
inline T embree_eval(EmbreeQuery<T>& q, V3<T> p, std::uint32_t f) {
  const std::uint32_t* t = q.t + 3 * static_cast<std::size_t>(f);
  T bary[3];
  const T d2 =
      closest_on_triangle(p, vertex(q.v, t[0]), vertex(q.v, t[1]), vertex(q.v, t[2]), bary);
  if (d2 < q.best) {
    q.best = d2;
    q.face = f;
    std::copy(bary, bary + 3, q.bary);
  }
  return d2;
}

template <class T>
bool embree_callback(RTCPointQueryFunctionArguments* args) {
  auto& q = *static_cast<EmbreeQuery<T>*>(args->userPtr);
  const T before = q.best;
  embree_eval(q, q.p, args->primID);
  if (q.best < before) {
    // Never below the true distance in float (the radius only prunes).
    args->query->radius = std::nextafter(static_cast<float>(std::sqrt(q.best)),
                                         std::numeric_limits<float>::infinity());
    return true;  // the radius shrank
  }
  return false;
}

struct EmbreeScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  EmbreeScene(const EmbreeArrays& a, int threads) {
    const std::string config = "threads=" + std::to_string(threads);
    device = rtcNewDevice(config.c_str());
    if (!device) throw std::runtime_error("rtcNewDevice failed");
    scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_LOW);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_LOW);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, a.vertices.data(),
                               0, 3 * sizeof(float), (a.vertices.size() - 1) / 3);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, a.tris.data(), 0,
                               3 * sizeof(std::uint32_t), a.tris.size() / 3);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
  }
  void commit() { rtcCommitScene(scene); }
  ~EmbreeScene() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
};

// The peers' loops deal their samples to the team as meshdev's deviation loop deals its own
// (metric/chunk_schedule.h): chunks of kPeerChunk, each thread a contiguous range of them, the
// others' last chunks taken once its own are spent. Embree's times were the same as with
// OpenMP's schedule(dynamic, 1024) (2 threads, best of 3, three alternations: torus100k -> 1m
// 2.60-2.64 against 2.59-2.62 M/s, torus1m -> 100k 2.58-2.66 against 2.54-2.66, torus100k -> 10k
// 3.28 against 3.24-3.26; docs/performance-log.md §3).
constexpr std::int64_t kPeerChunk = 1024;
std::int64_t peer_chunks(std::int64_t n) {
  return (n + kPeerChunk - 1) / kPeerChunk;
}

template <class T>
void embree_queries(RTCScene scene, const T* vertices, const std::uint32_t* tris,
                    const std::vector<float>& attr, const std::vector<float>& points,
                    const std::vector<double>& points_d, bool hint, int threads, PeerOut& out) {
  const auto n = static_cast<std::int64_t>(points.size() / 3);
  std::unique_ptr<meshdev::ChunkSchedule> schedule;
#pragma omp parallel num_threads(threads)
  {
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    std::uint32_t previous = std::numeric_limits<std::uint32_t>::max();
#pragma omp single
    schedule = std::make_unique<meshdev::ChunkSchedule>(peer_chunks(n), omp_get_num_threads());
    for (std::int64_t chunk; (chunk = schedule->next(omp_get_thread_num())) >= 0;)
      for (std::int64_t i = chunk * kPeerChunk; i < std::min(n, (chunk + 1) * kPeerChunk); ++i) {
        RTCPointQuery query;
        query.x = points[3 * i], query.y = points[3 * i + 1], query.z = points[3 * i + 2];
        query.time = 0;
        query.radius = std::numeric_limits<float>::infinity();
        EmbreeQuery<T> q{vertices,
                         tris,
                         {static_cast<T>(points_d[3 * i]), static_cast<T>(points_d[3 * i + 1]),
                          static_cast<T>(points_d[3 * i + 2])}};
        if (hint && previous != std::numeric_limits<std::uint32_t>::max()) {
          // The coherence bound meshdev uses: the previous sample's triangle gives an upper bound.
          embree_eval(q, q.p, previous);
          query.radius = std::nextafter(static_cast<float>(std::sqrt(q.best)),
                                        std::numeric_limits<float>::infinity());
        }
        rtcPointQuery(scene, &query, &context, embree_callback<T>, &q);
        previous = q.face;
        const std::uint32_t* t = tris + 3 * static_cast<std::size_t>(q.face);
        out.distance[i] = static_cast<float>(std::sqrt(q.best));
        out.face[i] = q.face;
        for (int k = 0; k < 3; ++k)
          out.attribute[3 * i + k] =
              static_cast<float>(q.bary[0] * attr[3 * t[0] + k] + q.bary[1] * attr[3 * t[1] + k] +
                                 q.bary[2] * attr[3 * t[2] + k]);
      }
  }
}

// ---------------------------------------------------------------------------------------------
// CGAL AABB tree.

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalTriangles = std::vector<K::Triangle_3>;
using CgalPrimitive = CGAL::AABB_triangle_primitive<K, CgalTriangles::const_iterator>;
using CgalTree = CGAL::AABB_tree<CGAL::AABB_traits<K, CgalPrimitive>>;

void cgal_queries(const CgalTree& tree, const CgalTriangles& tris, const meshdev::TriMesh& b,
                  const std::vector<double>& attr, const std::vector<double>& points, int threads,
                  PeerOut& out) {
  const auto n = static_cast<std::int64_t>(points.size() / 3);
  std::unique_ptr<meshdev::ChunkSchedule> schedule;
#pragma omp parallel num_threads(threads)
  {
#pragma omp single
    schedule = std::make_unique<meshdev::ChunkSchedule>(peer_chunks(n), omp_get_num_threads());
    for (std::int64_t chunk; (chunk = schedule->next(omp_get_thread_num())) >= 0;)
      for (std::int64_t i = chunk * kPeerChunk; i < std::min(n, (chunk + 1) * kPeerChunk); ++i) {
        const K::Point_3 p(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
        const auto hit = tree.closest_point_and_primitive(p);
        const auto f = static_cast<std::uint32_t>(hit.second - tris.begin());
        // Barycentrics of the closest point on face f (projection; it lies on the triangle).
        const auto& t = b.faces[f];
        const Vec3 a0 = b.positions[t[0]], e1 = b.positions[t[1]] - a0, e2 = b.positions[t[2]] - a0;
        const Vec3 r = Vec3{hit.first.x(), hit.first.y(), hit.first.z()} - a0;
        const double d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2);
        const double d20 = dot(r, e1), d21 = dot(r, e2);
        const double den = d00 * d11 - d01 * d01;
        double v = 0, w = 0;
        if (den > 0) v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
        const double u = 1 - v - w;
        out.distance[i] = static_cast<float>(std::sqrt(CGAL::squared_distance(p, hit.first)));
        out.face[i] = f;
        for (int k = 0; k < 3; ++k)
          out.attribute[3 * i + k] = static_cast<float>(
              u * attr[3 * t[0] + k] + v * attr[3 * t[1] + k] + w * attr[3 * t[2] + k]);
      }
  }
}

// ---------------------------------------------------------------------------------------------
// Reporting.

struct Row {
  Row(std::string e, int th, double b, Timing t, double q)
      : engine(std::move(e)), threads(th), build(b), query(t), qps(q) {}
  std::string engine;
  int threads = 1;
  double build = 0;  // seconds (the structure used by this row)
  Timing query;
  double qps = 0;
  double mean = 0, max = 0;
  double bytes_per_face = 0;  // structure: meshdev exact, peers from the RSS delta
  double struct_mib = 0;
  std::string note;
};

struct Options {
  std::string a, b, label;
  std::size_t samples = 1000000;
  std::uint64_t seed = 1;
  std::string order = "morton";  // the samples' order: morton, hilbert or native (the sampler's)
  std::vector<int> threads{1, 2};
  int repeats = 3;
  std::vector<std::string> engines{"meshdev", "embree", "cgal"};
  bool embree_hint = false;
  bool embree_float = false;
  int rounds = 0;  // > 0: also time meshdev and Embree alternately, this many rounds (main())
  int ab = 0;      // > 0: only meshdev's variants 0 and 1, this many rounds (run_ab)
  std::size_t ab_chunk = 65536;  // samples per chunk of --ab
  bool ab_build = false;         // --ab-build: each variant queries an index built under it
  std::string csv;
  std::string rounds_csv;  // --rounds-csv: one CSV row per round
  double check = -1.0;     // --check: the largest per-sample disagreement allowed (< 0: none)
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

[[noreturn]] void usage() {
  std::fprintf(stderr,
               "usage: peer_compare A B N [--seed S] [--order morton|hilbert|native]\n"
               "                          [--threads 1,2] [--repeats 3]\n"
               "                          [--engines meshdev,embree,cgal]\n"
               "                          [--embree-hint] [--embree-float]\n"
               "                          [--rounds R [--rounds-csv FILE]] [--csv FILE]\n"
               "                          [--label NAME]\n"
               "                          [--ab R [--ab-chunk C] [--ab-build]] [--check REL]\n");
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> pos;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) usage();
      return argv[++i];
    };
    if (s == "--seed")
      o.seed = std::stoull(next());
    else if (s == "--order") {
      const std::string v = next();
      if (v != "morton" && v != "hilbert" && v != "native") usage();
      o.order = v;
    } else if (s == "--threads") {
      o.threads.clear();
      for (const auto& t : split(next())) o.threads.push_back(std::stoi(t));
    } else if (s == "--repeats")
      o.repeats = std::max(1, std::stoi(next()));
    else if (s == "--engines")
      o.engines = split(next());
    else if (s == "--embree-hint")
      o.embree_hint = true;
    else if (s == "--embree-float")
      o.embree_float = true;
    else if (s == "--rounds")
      o.rounds = std::max(0, std::stoi(next()));
    else if (s == "--ab")
      o.ab = std::max(0, std::stoi(next()));
    else if (s == "--ab-build")
      o.ab_build = true;
    else if (s == "--ab-chunk")
      o.ab_chunk = std::max<std::size_t>(1, std::stoull(next()));
    else if (s == "--csv")
      o.csv = next();
    else if (s == "--rounds-csv")
      o.rounds_csv = next();
    else if (s == "--label")
      o.label = next();
    else if (s == "--check") {
      const std::string v = next();
      char* end = nullptr;
      o.check = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(o.check >= 0.0)) usage();
    } else if (!s.empty() && s[0] == '-')
      usage();
    else
      pos.push_back(s);
  }
  if (pos.size() != 3) usage();
  if (!o.rounds_csv.empty() && o.rounds == 0) usage();
  if (o.check >= 0.0 && (o.engines.size() < 2 || o.ab > 0)) usage();
  o.a = pos[0], o.b = pos[1], o.samples = std::stoull(pos[2]);
  return o;
}

bool wants(const Options& o, const std::string& engine) {
  return std::find(o.engines.begin(), o.engines.end(), engine) != o.engines.end();
}

std::string basename(const std::string& p) {
  const auto s = p.find_last_of('/');
  return s == std::string::npos ? p : p.substr(s + 1);
}

template <class T, class Allocator>
std::pair<double, double> mean_max(const std::vector<T, Allocator>& d) {
  double sum = 0, mx = 0;
  for (T x : d) sum += static_cast<double>(x), mx = std::max(mx, static_cast<double>(x));
  return {d.empty() ? 0 : sum / static_cast<double>(d.size()), mx};
}

double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// Appends `rows` to the CSV file at `path`, with `header` first if the file is new or empty.
// False (with a message on stderr) if the file cannot be written, or if it starts with another
// header (a file of an older format: its columns would not match the rows').
bool append_csv(const std::string& path, const char* header, const std::string& rows) {
  std::ifstream probe(path);
  const bool fresh = !probe.good() || probe.peek() == std::ifstream::traits_type::eof();
  if (!fresh) {
    std::string first;
    std::getline(probe, first);
    if (first + "\n" != header) {
      std::fprintf(stderr, "peer_compare: %s has other columns than these rows (%s); not written\n",
                   path.c_str(), first.c_str());
      return false;
    }
  }
  probe.close();
  std::ofstream f(path, std::ios::app);
  if (fresh) f << header;
  f << rows;
  f.close();
  if (!f) std::fprintf(stderr, "peer_compare: cannot write %s\n", path.c_str());
  return static_cast<bool>(f);
}

// The last line of an A/B: the median and range of the rounds' ratios (variant 0 / variant 1).
void print_ab_summary(int th, const char* what, const std::vector<double>& ratio) {
  const auto [lo, hi] = std::minmax_element(ratio.begin(), ratio.end());
  std::printf("%3d %smedian v0/v1 %.4f (range %.4f-%.4f) over %zu rounds\n", th, what,
              median_of(ratio), *lo, *hi, ratio.size());
}

// --ab R --ab-build (see the top of this file): B's index built under variant 0 and under
// variant 1, in turn, R times over per thread count (which goes first alternating), each round's
// times and ratio printed. Returns each variant's last index.
std::array<std::unique_ptr<meshdev::NearestPointIndex>, 2> build_ab(const Options& opt,
                                                                    const meshdev::TriMesh& b) {
  std::array<std::unique_ptr<meshdev::NearestPointIndex>, 2> built;
  std::printf("A/B of the build of B (%zu faces):\n%3s %5s %12s %12s %12s\n", b.num_faces(), "thr",
              "round", "v0 build s", "v1 build s", "v0/v1 time");
  for (int th : opt.threads) {
    std::vector<double> ratio;
    for (int r = 0; r < opt.ab; ++r) {
      double t[2];
      for (int v : {r % 2, 1 - r % 2}) {
        meshdev::detail::set_ab_variant(v);
        built[v].reset();  // (freeing the last one is not part of the build)
        const auto t0 = Clock::now();
        built[v] = meshdev::make_nearest_point_index(b, meshdev::IndexKind::kBvh, {}, th);
        t[v] = seconds_since(t0);
      }
      ratio.push_back(t[0] / t[1]);
      std::printf("%3d %5d %12.4f %12.4f %12.4f\n", th, r + 1, t[0], t[1], t[0] / t[1]);
    }
    print_ab_summary(th, "build ", ratio);
  }
  meshdev::detail::set_ab_variant(0);
  return built;
}

// --ab R (see the top of this file): meshdev's variants 0 and 1 chunk-interleaved, variant v
// answered by index[v]. Returns the process's exit status: 1 if the variants' results differ.
int run_ab(const Options& opt, const meshdev::SampleSet& set, const meshdev::AttributePlan& plan,
           const meshdev::NearestPointIndex* const index[2]) {
  std::vector<meshdev::SampleSet> chunks;
  for (std::size_t begin = 0; begin < set.samples.size(); begin += opt.ab_chunk) {
    const std::size_t end = std::min(set.samples.size(), begin + opt.ab_chunk);
    meshdev::SampleSet chunk;
    chunk.samples.assign(set.samples.begin() + static_cast<std::ptrdiff_t>(begin),
                         set.samples.begin() + static_cast<std::ptrdiff_t>(end));
    chunk.step = set.step;
    chunk.face_count = end - begin;
    chunk.equal_weight = set.equal_weight;
    chunk.description = set.description;
    chunks.push_back(std::move(chunk));
  }
  auto run = [&](const meshdev::SampleSet& chunk, int variant, int th) {
    meshdev::detail::set_ab_variant(variant);
    meshdev::DeviationOptions options;  // as meshdev_queries in main()
    options.threads = th;
    options.keep_nearest = false;
    return meshdev::compute_deviations(chunk, plan.a, plan.b, *index[variant], plan.measures,
                                       options);
  };
  // Both variants' answers, compared once (deviations bit for bit, tie counts).
  std::size_t differ = 0;
  for (const meshdev::SampleSet& chunk : chunks) {
    const meshdev::SampleDeviations d0 = run(chunk, 0, opt.threads.back());
    const meshdev::SampleDeviations d1 = run(chunk, 1, opt.threads.back());
    for (std::size_t i = 0; i < chunk.samples.size(); ++i) {
      bool same = d0.tie_count[i] == d1.tie_count[i];
      for (std::size_t m = 0; m < d0.values.size(); ++m)
        same = same && std::memcmp(&d0.values[m][i], &d1.values[m][i], sizeof(double)) == 0;
      differ += same ? 0 : 1;
    }
  }
  std::printf("\nA/B (variant 0 = present code, 1 = candidate), %zu chunks of <= %zu samples: ",
              chunks.size(), opt.ab_chunk);
  if (differ > 0)
    std::printf("RESULTS DIFFER for %zu of %zu samples\n", differ, set.samples.size());
  else
    std::printf("same deviations and tie counts, bit for bit\n");
  std::printf("%3s %5s %12s %12s %12s\n", "thr", "round", "v0 M q/s", "v1 M q/s", "v0/v1 time");
  const double n = static_cast<double>(set.samples.size());
  for (int th : opt.threads) {
    std::vector<double> ratio;
    for (int r = 0; r < opt.ab; ++r) {
      double t[2] = {0.0, 0.0};
      for (std::size_t c = 0; c < chunks.size(); ++c) {
        const int first = static_cast<int>((c + static_cast<std::size_t>(r)) % 2);
        for (int v : {first, 1 - first}) {
          const auto t0 = Clock::now();
          run(chunks[c], v, th);
          t[v] += seconds_since(t0);
        }
      }
      ratio.push_back(t[0] / t[1]);
      std::printf("%3d %5d %12.3f %12.3f %12.4f\n", th, r + 1, n / t[0] / 1e6, n / t[1] / 1e6,
                  t[0] / t[1]);
    }
    print_ab_summary(th, "", ratio);
  }
  meshdev::detail::set_ab_variant(0);
  return differ > 0 ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  // glibc as the meshdev program sets it (apps/meshdev.cpp): large blocks from the heap, and freed
  // memory kept by the process, so a repeat's deviation arrays (37 MB for 1M samples) reuse the
  // pages of the run before instead of faulting fresh ones in (4,500 faults per run of 1M
  // samples without it; the peers write into arrays allocated once, outside their timed loops).
  // A failure (mallopt returns 0) costs speed only.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
  const Options opt = parse(argc, argv);
  const std::string load_start = loadavg();

  // Meshes, the extra attribute, the samples.
  meshdev::TriMesh a = meshdev::read_mesh(opt.a);
  meshdev::TriMesh b = meshdev::read_mesh(opt.b);
  const meshdev::BoundingBox box_a = meshdev::bounding_box(a);
  std::string temperature = "file";
  auto has_temp = [](const meshdev::TriMesh& m) {
    const auto* c = m.channel("temperature");
    return c && c->dim == 1 && c->storage == meshdev::Storage::kPerVertex;
  };
  if (!has_temp(a) || !has_temp(b)) {
    add_temperature(a, box_a);
    add_temperature(b, box_a);
    temperature = "generated";
  }
  meshdev::SamplingOptions so;
  so.vertices = so.edges = false;
  so.faces = meshdev::FaceSampling::kMonteCarlo;
  so.target_count = opt.samples;
  so.seed = opt.seed;
  auto t0 = Clock::now();
  meshdev::SampleSet set = meshdev::sample_surface(a, so, box_a.diagonal());
  const double t_sample = seconds_since(t0);
  t0 = Clock::now();
  if (opt.order != "native") curve_sort(set, box_a, opt.order == "hilbert");
  const double t_sort = seconds_since(t0);
  const std::size_t n = set.samples.size();

  std::printf("peer_compare: A = %s (%zu faces), B = %s (%zu faces)\n", opt.a.c_str(),
              a.num_faces(), opt.b.c_str(), b.num_faces());
  std::printf(
      "  %zu samples on A (Monte Carlo, seed %llu, %s order; sampling %.3f s, sort %.3f "
      "s), temperature channel: %s\n",
      n, static_cast<unsigned long long>(opt.seed), order_name(opt.order), t_sample, t_sort,
      temperature.c_str());
  std::printf(
      "  load average at start: %s (2-core machine: > 0.5 means the numbers are "
      "loaded)\n",
      load_start.c_str());
  std::fflush(stdout);

  std::vector<Row> rows;
  // meshdev's builds against its queries: the process's first build (the table's, made once on
  // OpenMP's default team), and per thread count the first query run and the best of --repeats
  // further builds on that count.
  double first_build = 0;
  long first_build_faults = 0;  // minor page faults during it
  struct BuildAgainstQuery {
    int threads;
    double first_query, best_build, best_query;
  };
  std::vector<BuildAgainstQuery> build_vs_query;
  std::vector<double> d_meshdev;
  std::vector<float> d_embree, d_cgal;
  std::vector<float> attr_f;   // B's normals, 3 floats per vertex (the peers' attribute)
  std::vector<double> attr_d;  // same in double (CGAL)
  double meshdev_ties = 0;

  // The attribute plan also gives B's normals (computed the same way for the peers' attribute).
  meshdev::AttributeOptions ao;
  ao.attributes = {"geometry", "normal", "temperature"};
  t0 = Clock::now();
  const meshdev::AttributePlan plan = meshdev::plan_attributes(a, b, ao, "A", "B");
  const double t_plan = seconds_since(t0);
  {
    const meshdev::AttributeChannel* nb = plan.b.channel("normal");
    attr_d.assign(3 * b.num_vertices(), 0.0);
    if (nb && nb->storage == meshdev::Storage::kPerVertex && nb->dim == 3)
      attr_d.assign(nb->values.begin(), nb->values.end());
    else
      for (std::size_t v = 0; v < b.num_vertices(); ++v) attr_d[3 * v] = 1;
    attr_f.assign(attr_d.begin(), attr_d.end());
  }

  if (opt.ab > 0) {
    std::array<std::unique_ptr<meshdev::NearestPointIndex>, 2> built;
    if (opt.ab_build)
      built = build_ab(opt, b);
    else
      built[0] = meshdev::make_nearest_point_index(b, meshdev::IndexKind::kBvh);
    const meshdev::NearestPointIndex* const index[2] = {built[0].get(),
                                                        (built[1] ? built[1] : built[0]).get()};
    return run_ab(opt, set, plan, index);
  }

  // The timed loops: meshdev's whole compute_deviations call, Embree's queries (exact callback
  // in double on our positions, or in float with --embree-float).
  auto meshdev_queries = [&](const meshdev::NearestPointIndex& index, int th) {
    meshdev::DeviationOptions options;  // what `meshdev compare` asks for
    options.threads = th;
    options.keep_nearest = false;
    return meshdev::compute_deviations(set, plan.a, plan.b, index, plan.measures, options);
  };
  std::vector<float> pf;  // the query points for the peers, in the same order (filled below)
  std::vector<double> pd;
  auto embree_run = [&](const EmbreeArrays& arrays, RTCScene scene, bool hint, int th,
                        PeerOut& out) {
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 is read as a double array");
    if (!opt.embree_float)
      embree_queries(scene, &b.positions[0].x, arrays.tris.data(), attr_f, pf, pd, hint, th, out);
    else
      embree_queries(scene, arrays.vertices.data(), arrays.tris.data(), attr_f, pf, pd, hint, th,
                     out);
  };

  // (a) meshdev.
  if (wants(opt, "meshdev")) {
    const MemProbe probe;
    const long faults0 = minor_faults();
    t0 = Clock::now();
    auto index = meshdev::make_nearest_point_index(b, meshdev::IndexKind::kBvh);
    const double build = seconds_since(t0);
    first_build = build;
    first_build_faults = minor_faults() - faults0;
    const double struct_mib = probe.mib();
    const auto* bvh = dynamic_cast<const meshdev::TriangleBvh*>(index.get());
    const double bpf =
        bvh ? static_cast<double>(bvh->memory_bytes()) / static_cast<double>(b.num_faces()) : 0;
    for (int th : opt.threads) {
      meshdev::SampleDeviations dev;
      const Timing t = time_best(opt.repeats, th, [&] { dev = meshdev_queries(*index, th); });
      Row r{"meshdev", th, build, t, static_cast<double>(n) / t.wall};
      std::tie(r.mean, r.max) = mean_max(dev.values[0]);
      r.bytes_per_face = bpf;
      r.struct_mib = bvh ? static_cast<double>(bvh->memory_bytes()) / 1048576.0 : struct_mib;
      r.note = "index " + index->name() + ", plan " + std::to_string(t_plan).substr(0, 5) + " s";
      rows.push_back(r);
      double best_build = std::numeric_limits<double>::infinity();
      for (int k = 0; k < opt.repeats; ++k) {
        const auto b0 = Clock::now();
        auto again = meshdev::make_nearest_point_index(b, meshdev::IndexKind::kBvh, {}, th);
        best_build = std::min(best_build, seconds_since(b0));
      }  // (freeing each one is not part of its build)
      build_vs_query.push_back({th, t.first, best_build, t.wall});
      if (d_meshdev.empty()) {
        d_meshdev.assign(dev.values[0].begin(), dev.values[0].end());
        double ties = 0;
        for (auto c : dev.tie_count) ties += c;
        meshdev_ties = ties / static_cast<double>(n);
      }
    }
  }

  // Query points for the peers, in the same order.
  pf.resize(3 * n);
  pd.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = set.samples[i].point;
    for (int k = 0; k < 3; ++k) {
      pd[3 * i + k] = p[k];
      pf[3 * i + k] = static_cast<float>(p[k]);
    }
  }

  // (b) Embree 3.
  if (wants(opt, "embree")) {
    const EmbreeArrays arrays = embree_arrays(b);
    PeerOut out;
    out.resize(n);
    double embree_mib = -1;
    std::vector<bool> variants{false};
    if (opt.embree_hint) variants.push_back(true);
    for (int th : opt.threads) {
      // Best-of build with the device's pool limited to `th` threads; keep the last scene.
      double build = std::numeric_limits<double>::infinity();
      std::unique_ptr<EmbreeScene> scene;
      for (int r = 0; r < opt.repeats; ++r) {
        scene.reset();
        scene = std::make_unique<EmbreeScene>(arrays, th);  // device, thread pool, geometry
        const MemProbe probe;                               // so the growth is the BVH only
        t0 = Clock::now();
        scene->commit();
        build = std::min(build, seconds_since(t0));
        if (embree_mib < 0) embree_mib = probe.mib();  // the first build, on fresh memory
      }
      for (bool hint : variants) {
        const Timing t =
            time_best(opt.repeats, th, [&] { embree_run(arrays, scene->scene, hint, th, out); });
        Row r{hint ? "embree+hint" : "embree", th, build, t, static_cast<double>(n) / t.wall};
        std::tie(r.mean, r.max) = mean_max(out.distance);
        r.struct_mib = embree_mib;
        r.bytes_per_face = embree_mib * 1048576.0 / static_cast<double>(b.num_faces());
        r.note = std::string(order_name(opt.order)) + " order, LOW build" +
                 (hint ? ", previous-face bound" : "") +
                 (opt.embree_float ? ", float callback" : ", double callback");
        rows.push_back(r);
        if (d_embree.empty()) d_embree = out.distance;
      }
    }
  }

  // (c) CGAL AABB tree (Epick) with the KD-tree accelerator.
  if (wants(opt, "cgal")) {
    CgalTriangles tris;
    tris.reserve(b.num_faces());
    auto point = [&](std::uint32_t v) {
      const Vec3& p = b.positions[v];
      return K::Point_3(p.x, p.y, p.z);
    };
    for (const auto& f : b.faces) tris.emplace_back(point(f[0]), point(f[1]), point(f[2]));
    const MemProbe probe;
    t0 = Clock::now();
    CgalTree tree(tris.begin(), tris.end());
    tree.build();
    const double t_tree = seconds_since(t0);
    t0 = Clock::now();
    tree.accelerate_distance_queries();
    tree.closest_point(K::Point_3(pd[0], pd[1], pd[2]));  // makes sure the KD-tree is built
    const double t_kd = seconds_since(t0);
    const double struct_mib = probe.mib();
    PeerOut out;
    out.resize(n);
    for (int th : opt.threads) {
      const Timing t =
          time_best(opt.repeats, th, [&] { cgal_queries(tree, tris, b, attr_d, pd, th, out); });
      Row r{"cgal", th, t_tree + t_kd, t, static_cast<double>(n) / t.wall};
      std::tie(r.mean, r.max) = mean_max(out.distance);
      r.struct_mib = struct_mib;
      r.bytes_per_face = struct_mib * 1048576.0 / static_cast<double>(b.num_faces());
      char note[96];
      std::snprintf(note, sizeof note, "tree %.3f s + KD-tree %.3f s", t_tree, t_kd);
      r.note = note;
      rows.push_back(r);
      if (d_cgal.empty()) d_cgal = out.distance;
    }
  }

  // Agreement.
  // Two engines' per-sample distances, one pass: the largest finite |difference| (NaN if either
  // engine has no distance per sample), and how many samples differ by more than `allowed` or
  // have a distance that is not finite (all n if the counts differ; none if either did not run).
  struct Disagreement {
    double largest = std::numeric_limits<double>::quiet_NaN();
    std::size_t bad = 0;
    bool compared = false;
  };
  auto disagreement = [&](const auto& x, const auto& y, double allowed) {
    Disagreement d;
    if (x.empty() || y.empty()) return d;
    d.compared = true;
    if (x.size() != n || y.size() != n) {
      d.bad = n;
      return d;
    }
    d.largest = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double dx = static_cast<double>(x[i]), dy = static_cast<double>(y[i]);
      const double diff = std::abs(dx - dy);
      if (!std::isfinite(dx) || !std::isfinite(dy) || !(diff <= allowed)) ++d.bad;
      if (std::isfinite(diff)) d.largest = std::max(d.largest, diff);
    }
    return d;
  };
  double mean_lo = std::numeric_limits<double>::infinity(), mean_hi = -mean_lo;
  for (const Row& r : rows)
    mean_lo = std::min(mean_lo, r.mean), mean_hi = std::max(mean_hi, r.mean);
  const double mean_diff = rows.empty() ? 0 : mean_hi - mean_lo;
  const double diag_b = meshdev::bounding_box(b).diagonal();
  // --check's limit; without it only distances that are not finite count as bad.
  const double allowed =
      opt.check >= 0.0 ? opt.check * diag_b : std::numeric_limits<double>::infinity();
  const Disagreement me = disagreement(d_meshdev, d_embree, allowed),
                     mc = disagreement(d_meshdev, d_cgal, allowed),
                     ec = disagreement(d_embree, d_cgal, allowed);

  // meshdev's ratio over each peer at the same thread count.
  auto meshdev_qps = [&](int th) {
    for (const Row& r : rows)
      if (r.engine == "meshdev" && r.threads == th) return r.qps;
    return std::numeric_limits<double>::quiet_NaN();
  };
  // Samples per CPU-second actually consumed: on a loaded machine (CPU share < 1) this is the
  // fairer basis for a ratio; on a quiet one it equals qps / threads.
  auto per_cpu = [&](const Row& r) { return r.qps / (r.query.share * r.threads); };
  auto meshdev_per_cpu = [&](int th) {
    for (const Row& r : rows)
      if (r.engine == "meshdev" && r.threads == th) return per_cpu(r);
    return std::numeric_limits<double>::quiet_NaN();
  };

  const std::string load_end = loadavg();
  const double peak = peak_rss_mib();
  std::printf("\n%-12s %3s %8s %8s %8s %5s %9s %9s %9s %11s %7s %7s  %s\n", "engine", "thr",
              "build s", "query s", "M q/s", "cpu", "M q/CPUs", "meshdev/x", "(per CPU)",
              "mean dist", "B/face", "MiB", "notes");
  for (const Row& r : rows) {
    std::printf("%-12s %3d %8.4f %8.4f %8.3f %5.2f %9.3f %9.2f %9.2f %11.6g %7.1f %7.1f  %s\n",
                r.engine.c_str(), r.threads, r.build, r.query.wall, r.qps / 1e6, r.query.share,
                per_cpu(r) / 1e6, meshdev_qps(r.threads) / r.qps,
                meshdev_per_cpu(r.threads) / per_cpu(r), r.mean, r.bytes_per_face, r.struct_mib,
                r.note.c_str());
  }
  std::printf(
      "(M q/s: wall-clock throughput; cpu: CPU share = CPU s / (wall x threads); M q/CPUs: "
      "samples per CPU-second; meshdev/x: meshdev's throughput over this row's, wall and "
      "per CPU-second; B/face: structure bytes per face of B, meshdev exact "
      "(TriangleBvh::memory_bytes), peers from the heap or RSS growth of their build)\n");
  auto speedup = [&](const std::string& e) {
    double q1 = 0, q2 = 0;
    for (const Row& r : rows)
      if (r.engine == e && r.threads == 1)
        q1 = r.qps;
      else if (r.engine == e && r.threads == 2)
        q2 = r.qps;
    return q1 > 0 && q2 > 0 ? q2 / q1 : std::numeric_limits<double>::quiet_NaN();
  };
  std::printf("\n2-thread speed-up: meshdev %.2fx, embree %.2fx, cgal %.2fx\n", speedup("meshdev"),
              speedup("embree"), speedup("cgal"));
  std::printf(
      "agreement: mean distance spread %.3g (%.3g of B's diagonal); max per-sample |d|"
      " difference meshdev-embree %.3g, meshdev-cgal %.3g, embree-cgal %.3g\n",
      mean_diff, diag_b > 0 ? mean_diff / diag_b : 0.0, me.largest, mc.largest, ec.largest);
  if (!d_meshdev.empty()) std::printf("meshdev: %.3f equidistant faces per sample\n", meshdev_ties);
  // --check: every pair of engines that ran, each sample's distances within check x B's
  // diagonal; a distance that is not finite, or an engine without one per sample, fails.
  bool agreed = true;
  if (opt.check >= 0.0) {
    double worst = 0.0;
    std::size_t bad = 0, pairs = 0;
    for (const Disagreement& d : {me, mc, ec}) {
      if (!d.compared) continue;
      ++pairs;
      bad += d.bad;
      if (std::isfinite(d.largest)) worst = std::max(worst, d.largest);
    }
    const std::size_t engines =
        std::size_t{!d_meshdev.empty()} + !d_embree.empty() + !d_cgal.empty();
    agreed = pairs > 0 && bad == 0;
    std::printf(
        "check (--check %g): %zu engines, largest per-sample |d| difference %.3g = %.3g of B's "
        "diagonal, %zu sample comparisons over the limit or not finite: %s\n",
        opt.check, engines, worst, diag_b > 0 ? worst / diag_b : 0.0, bad,
        agreed ? "passed" : "FAILED");
  }
  // The first build ran on OpenMP's default team; set against the first query on that many.
  if (!build_vs_query.empty()) {
    const int team = omp_get_max_threads();
    const auto same = std::find_if(build_vs_query.begin(), build_vs_query.end(),
                                   [&](const BuildAgainstQuery& bq) { return bq.threads == team; });
    if (same != build_vs_query.end())
      std::printf(
          "meshdev build of B (%zu faces) against the query of the %zu samples, %d threads: "
          "the process's first build %.4f s / first query run %.4f s = %.2f\n",
          b.num_faces(), n, team, first_build, same->first_query, first_build / same->first_query);
    else
      std::printf(
          "meshdev build of B (%zu faces): the process's first build %.4f s ran on %d threads, "
          "and no query row did (--threads): not set against a query\n",
          b.num_faces(), first_build, team);
    // Its first touches of fresh memory (later builds reuse what the one before freed): on a host
    // that backs a guest's memory lazily their cost varies from run to run (docs/performance.md
    // §2.3).
    std::printf("  (that first build took %ld minor page faults)\n", first_build_faults);
  }
  for (const BuildAgainstQuery& bq : build_vs_query)
    std::printf(
        "meshdev build of B against the query, %d thread(s): best of %d builds %.4f s / best "
        "query %.4f s = %.2f\n",
        bq.threads, opt.repeats, bq.best_build, bq.best_query, bq.best_build / bq.best_query);
  std::printf("peak RSS of the process %.1f MiB; load average at end: %s\n", peak,
              load_end.c_str());

  // The CSV rows' label.
  const std::string label =
      opt.label.empty() ? basename(opt.a) + "->" + basename(opt.b) : opt.label;

  // (d) Interleaved rounds: one run of meshdev, then of Embree (and Embree+hint), on each thread
  // count in turn, round after round, so that a drift of the machine's speed over the minutes of
  // a run (a shared host: 20-30 % seen within a session) falls on the engines, and on the thread
  // counts, alike. The thread counts go in reverse order every other round, so that neither
  // always runs first. Each run's ratio is printed, then per thread count their median and range,
  // and meshdev's speed-up over the first thread count, round by round.
  std::ostringstream rounds_csv;  // --rounds-csv rows
  if (opt.rounds > 0 && wants(opt, "meshdev") && wants(opt, "embree")) {
    auto index = meshdev::make_nearest_point_index(b, meshdev::IndexKind::kBvh);
    const EmbreeArrays arrays = embree_arrays(b);
    EmbreeScene scene(arrays, *std::max_element(opt.threads.begin(), opt.threads.end()));
    scene.commit();
    PeerOut out;
    out.resize(n);
    auto qps = [&](const Timing& t) { return static_cast<double>(n) / t.wall / 1e6; };
    std::printf(
        "\ninterleaved rounds (meshdev, embree%s, one run each per round and thread "
        "count):\n",
        opt.embree_hint ? ", embree+hint" : "");
    std::printf("%3s %5s %10s %10s %10s %12s %12s\n", "thr", "round", "meshdev", "embree",
                "embree+hint", "meshdev/emb", "meshdev/e+h");
    // One untimed run of each engine first: the first run after the index was built faulted in
    // the pages of its result arrays (torus100k -> 10k: 4,883 page faults, and 6.1-6.5 M/s
    // against 8.7-9.3 in the later 1-thread rounds), which only the first round paid.
    meshdev_queries(*index, opt.threads.back());
    embree_run(arrays, scene.scene, false, opt.threads.back(), out);
    if (opt.embree_hint) embree_run(arrays, scene.scene, true, opt.threads.back(), out);
    const std::size_t counts = opt.threads.size();
    // [thread count's position in opt.threads][round]
    std::vector<std::vector<double>> over(counts), over_hint(counts), meshdev_wall(counts),
        probe(counts), splits(counts);
    const Clock::time_point rounds_start = Clock::now();
    for (int r = 0; r < opt.rounds; ++r) {
      for (std::size_t step = 0; step < counts; ++step) {
        const std::size_t t = r % 2 == 0 ? step : counts - 1 - step;
        const int th = opt.threads[t];
        const double probe_s = pipes_probe(th);
        const double start_s = std::chrono::duration<double>(Clock::now() - rounds_start).count();
        double split = 1.0;
        const Timing m =
            time_best(1, th, [&] { split = thread_split(meshdev_queries(*index, th)); });
        const Timing e = time_best(1, th, [&] { embree_run(arrays, scene.scene, false, th, out); });
        Timing h{std::numeric_limits<double>::quiet_NaN(), 0};
        if (opt.embree_hint)
          h = time_best(1, th, [&] { embree_run(arrays, scene.scene, true, th, out); });
        meshdev_wall[t].push_back(m.wall);
        probe[t].push_back(probe_s);
        splits[t].push_back(split);
        over[t].push_back(e.wall / m.wall);
        if (opt.embree_hint) over_hint[t].push_back(h.wall / m.wall);
        std::printf("%3d %5d %10.3f %10.3f %10.3f %12.2f %12.2f\n", th, r + 1, qps(m), qps(e),
                    qps(h), e.wall / m.wall, h.wall / m.wall);
        char line[512];
        std::snprintf(line, sizeof line,
                      "%s,%s,%s,%zu,%zu,%zu,%s,%d,%d,%.1f,%.1f,%.1f,%.4f,%.4f,%s,%.3f,%.5f,%.3f\n",
                      label.c_str(), basename(opt.a).c_str(), basename(opt.b).c_str(),
                      a.num_faces(), b.num_faces(), n, opt.order.c_str(), th, r + 1, qps(m) * 1e6,
                      qps(e) * 1e6, qps(h) * 1e6, e.wall / m.wall, h.wall / m.wall,
                      load_start.substr(0, load_start.find(' ')).c_str(), start_s, probe_s, split);
        rounds_csv << line;
      }
    }
    for (std::size_t t = 0; t < counts; ++t) {
      const auto [lo, hi] = std::minmax_element(over[t].begin(), over[t].end());
      std::printf("%3d median meshdev/embree %.2f (range %.2f-%.2f)", opt.threads[t],
                  median_of(over[t]), *lo, *hi);
      if (!over_hint[t].empty()) {
        const auto [lo_h, hi_h] = std::minmax_element(over_hint[t].begin(), over_hint[t].end());
        std::printf(", meshdev/embree+hint %.2f (range %.2f-%.2f)", median_of(over_hint[t]), *lo_h,
                    *hi_h);
      }
      if (t > 0) {  // each round's speed-up: the first thread count's time over this one's
        std::vector<double> gain;
        for (int r = 0; r < opt.rounds; ++r)
          gain.push_back(meshdev_wall[0][r] / meshdev_wall[t][r]);
        const auto [lo_s, hi_s] = std::minmax_element(gain.begin(), gain.end());
        std::printf(", meshdev %d over %d threads %.2f (range %.2f-%.2f)", opt.threads[t],
                    opt.threads[0], median_of(gain), *lo_s, *hi_s);
        std::vector<double> host;  // the same for the probe before each run (ideal: the ratio
        for (int r = 0; r < opt.rounds; ++r)  // of the thread counts)
          host.push_back(probe[0][r] / probe[t][r]);
        const auto [lo_p, hi_p] = std::minmax_element(host.begin(), host.end());
        std::printf(", the host's probe %.2f (range %.2f-%.2f)", median_of(host), *lo_p, *hi_p);
        const auto [lo_t, hi_t] = std::minmax_element(splits[t].begin(), splits[t].end());
        std::printf(", meshdev's thread split %.2f (range %.2f-%.2f)", median_of(splits[t]), *lo_t,
                    *hi_t);
      }
      std::printf(" over %d rounds\n", opt.rounds);
    }
  }

  // CSV.
  std::ostringstream csv;
  for (const Row& r : rows) {
    char line[1024];
    std::snprintf(line, sizeof line,
                  "%s,%s,%s,%zu,%zu,%zu,%s,%s,%d,%.6f,%.6f,%.1f,%.3f,%.1f,%d,%.9g,%.9g,%.2f,%.2f,"
                  "%.1f,%.3f,%.3f,%.3g,%s,%s\n",
                  label.c_str(), basename(opt.a).c_str(), basename(opt.b).c_str(), a.num_faces(),
                  b.num_faces(), n, opt.order.c_str(), r.engine.c_str(), r.threads, r.build,
                  r.query.wall, r.qps, r.query.share, per_cpu(r), opt.repeats, r.mean, r.max,
                  r.bytes_per_face, r.struct_mib, peak, meshdev_qps(r.threads) / r.qps,
                  meshdev_per_cpu(r.threads) / per_cpu(r), mean_diff,
                  load_start.substr(0, load_start.find(' ')).c_str(),
                  load_end.substr(0, load_end.find(' ')).c_str());
    csv << line;
  }
  const char* header =
      "label,a,b,a_faces,b_faces,samples,order,engine,threads,build_s,query_s,qps,cpu_share,"
      "qps_per_cpu_s,repeats,mean_distance,max_distance,struct_bytes_per_face,struct_mib,"
      "peak_rss_mib,meshdev_over_engine,meshdev_over_engine_per_cpu,mean_spread,load_start,"
      "load_end\n";
  std::printf("\nCSV\n%s%s", header, csv.str().c_str());
  bool written = opt.csv.empty() || append_csv(opt.csv, header, csv.str());
  // Embree+hint's columns are nan without --embree-hint.
  const char* rounds_header =
      "label,a,b,a_faces,b_faces,samples,order,threads,round,meshdev_qps,embree_qps,"
      "embree_hint_qps,meshdev_over_embree,meshdev_over_embree_hint,load_start,start_s,probe_s,"
      "thread_split\n";
  if (!opt.rounds_csv.empty())
    written = append_csv(opt.rounds_csv, rounds_header, rounds_csv.str()) && written;
  if (!agreed)
    std::fprintf(stderr, "peer_compare: the engines disagree on %s -> %s (--check %g)\n",
                 opt.a.c_str(), opt.b.c_str(), opt.check);
  return written && agreed ? 0 : 1;
}
