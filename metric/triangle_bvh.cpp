#include "metric/triangle_bvh.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>
#include <string>
#include <utility>

#include "metric/centre_bins.h"
#include "metric/face_boxes.h"
#include "metric/float_rounding.h"
#include "metric/key_ranks.h"
#include "metric/leaf_blocks.h"
#include "metric/morton_order.h"
#include "metric/plane_bounds.h"
#include "metric/query_frame.h"
#include "metric/simd4.h"
#include "metric/wide_collapse.h"

namespace meshdev {
namespace {

using simd::F4;

constexpr int kBins = 16;
constexpr std::uint32_t kLeafSize = 4;
constexpr std::uint32_t kAlignBelow = 32;       // subtrees this small split at multiples of 4
constexpr std::uint32_t kTaskBelow = 1u << 15;  // smaller subtrees are built by one thread
constexpr std::uint32_t kMinRun = 4;  // mean run of faces in one bin for the binning by runs
// Meshes of at least kMortonFrom faces stored in no spatial order are split along a Morton curve
// above kAlignBelow faces instead of by binned SAH (see sort_along_morton_curve).
constexpr std::uint32_t kMortonFrom = 4096;
constexpr int kMortonBits = 10;                  // per axis: 30-bit codes
constexpr int kOrderGrid = 16;                   // cells per axis of the order probe
constexpr std::uint32_t kOrderProbeStride = 64;  // the probe's pairs: faces 64i and 64i + 1
// Below this depth the binary build splits by SAH; deeper (only for pathological inputs) it splits
// the list in halves, so the depth stays below kMaxSahDepth + 33 and leaves keep <= 4 faces.
constexpr int kMaxSahDepth = 60;
constexpr int kMaxBinaryDepth = kMaxSahDepth + 33;
// Each 4-wide level pushes at most 3 entries more than it pops.
constexpr int kStackSize = 3 * kMaxBinaryDepth + 4;

constexpr std::uint32_t kLeafBit = detail::kWideLeafBit;
constexpr std::uint32_t kEmpty = detail::kWideEmpty;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr double kUnit = detail::kFloatUnit;  // unit roundoff of float (round to nearest)
// Slivers beyond kappa = kMaxKappa are never culled by the bound, nor triangles with
// |ab x ac|^2 below kMinNormal2 (float frame, where B spans [-1, 1]). That keeps |n| >= 1e-10 and
// |e| |n| >= 3e-21, so a float underflow anywhere in the bound (absolute error <= 2^-149 per
// operation, divided by at most |e| |n|) stays ~1e-24, far below the margin (>= 64 u 2 |e| >=
// 3e-16). The packets' planes (metric/plane_bounds.h) share both limits.
constexpr double kMaxKappa = kMaxCullKappa;
constexpr double kMinNormal2 = kMinCullNormal2;
// Meshes whose largest half extent is outside [kMinExtent, kMaxExtent] (absolute units) are never
// culled: their squared distances leave double's normal range (found by fuzz_nearest_point:
// faces 1e-300 apart all tie at a squared distance of 0 underflowed).
constexpr double kMinExtent = 1e-140;
constexpr double kMaxExtent = 1e140;

// Packets (find_batch): at most kPacketSize consecutive queries whose box diagonal is at most
// kPacketExtent mean longest edges of the target's faces (kFullPacketExtent once the packet holds
// kFullPacket queries): at least kMinPacket of them make a packet of faces (if their reach holds
// at most kMaxBlocks leaf blocks), kMinBlockPacket to kMinPacket - 1 (samples sparse on the target)
// a block packet (if their reach holds at most kMaxBlocks leaf blocks). The rest are answered one
// by one. With guessed reaches (below) the extent no longer widens the reach, and packets grew:
// 1 mean edge (block packets 2) before, 3 with the cut at 2 from 16 queries then
// (peer_compare --threads 1, M samples/s: torus100k -> torus1m 2.38-2.44 -> 2.67-2.78,
// buildings_s40k -> buildings in face order 3.49-3.51 -> 4.43-4.54, torus1m -> 100k 3.95-4.10 ->
// 4.46-4.47; 2 mean edges for both kinds was 2-4 % faster on the dense pairs but slower on the
// sparse ones; docs/performance-log.md §3). The minimum sizes went from 8 / 3 to 4 / 2 in the same
// way: buildings_s40k -> buildings 4.49-4.53 -> 4.85-4.93, torus100k -> torus1m and armadillo
// +2-3 %, the rest within 1 %. Since then the engine changed, and packets sparse on B gained from
// growing further: 4 mean edges until they hold 24 queries instead of 3 until 16 (`peer_compare
// A B 1000000 --ab 8|12`, 1 / 2 threads: torus100k -> 1m 1.021 / 1.023 and 1.022 / 1.026, ->
// torus1m_shuffled 1.021 / 1.017, the other five pairs 0.995-1.010; 4 mean edges throughout gave
// torus100k -> 1m 1.026 / 1.035 but torus1m -> 100k 0.950 / 0.959, whose dense packets hold 44
// queries; docs/performance-log.md §3, forty-fourth session).
constexpr std::size_t kPacketSize = 64;
constexpr std::size_t kMinPacket = 4;
constexpr double kPacketExtent = 4.0;
constexpr std::size_t kFullPacket = 24;
constexpr double kFullPacketExtent = 2.0;
constexpr std::size_t kMinBlockPacket = 2;
// Samples far from B give packets whose reach holds many leaf blocks; beyond kMaxBlocks their
// queries are answered one by one. 64 -> 128 blocks (`meshdev compare buildings.ply
// buildings_s40k.ply`, default sampling: queries of such packets 233k -> 104k of 8.2M; its
// queries 2-6 % faster; peer_compare --ab 8 buildings_s40k -> buildings +3.5 %, the other pairs
// within 1 %); 256 was no faster than 128 (docs/performance-log.md §3, twenty-fifth session).
constexpr std::size_t kMaxBlocks = 128;
constexpr std::size_t kDenseQueries = 3;
// A packet's guess of its queries' distances: this factor times the largest distance of the
// answers before it (used where it is less than half the packet's diagonal); the next packet
// answers its centre in full instead where more than one query in kGuessMisses was farther than
// guessed. (Factors 1.5 / 2 / 3 / 4 / 6 / 10 on torus100k -> torus1m: 2.25 / 2.32 / 2.42 / 2.37 /
// 2.26 / 2.34 M queries/s on one thread; 3 was as good or best on the other pairs measured.)
constexpr double kGuessFactor = 3.0;
constexpr std::size_t kGuessMisses = 4;
// "The largest distance of the answers before it" remembers earlier packets too, fading by this
// factor per packet: the largest of the last packet's distances and kGuessDecay times the value
// before. Samples along a Morton curve pass from where A and B are close to where they are far
// and back (torus100k on torus1m: 0 at A's vertices, the most at its faces' centres); a guess
// from the last packet alone then fell short for queries farther than it (about 1.8 % of the
// queries there, each then searched from the root). Chunk-interleaved, 2 threads, 8-10 runs:
// torus100k -> 1m +3.4 % (decays 0.5 / 0.8 / 0.9 / 0.95: +2.0 / +3.4 / +2.2 / +2.2 %), the
// other five pairs of docs/performance.md -0.5 % to +1.6 % (docs/performance-log.md §3).
constexpr double kGuessDecay = 0.8;

// A float box; extending by float coordinates is exact.
struct Box {
  float lo[3] = {kInf, kInf, kInf};
  float hi[3] = {-kInf, -kInf, -kInf};
  void extend(const Box& b) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], b.lo[k]);
      hi[k] = std::max(hi[k], b.hi[k]);
    }
  }
  void extend(const float p[3]) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  double half_area() const {
    if (!(lo[0] <= hi[0])) return 0.0;
    const double dx = double(hi[0]) - lo[0], dy = double(hi[1]) - lo[1], dz = double(hi[2]) - lo[2];
    return dx * dy + dy * dz + dz * dx;
  }
};

// One face during the build, 32 bytes (metric/face_boxes.h): its box in the float frame, rounded
// outwards (so node boxes made of them are conservative), with the face index's bits in the fourth
// lane of lo (the SSE box unions and centre sums carry that lane along and never read it). The
// build partitions these in place, so every pass over a range reads memory in order. lo + hi,
// twice the box centre, places the face.
using Prim = detail::FaceBox;
std::uint32_t face_of(const Prim& prim) {
  std::uint32_t f;
  std::memcpy(&f, &prim.lo[3], sizeof f);
  return f;
}
F4 centre2(const Prim& prim) {
  return F4::load(prim.lo) + F4::load(prim.hi);
}
// The centre key along `axis`; NaN (boxes reaching +-inf, only on meshes never culled) is 0.
float centre_key(const Prim& prim, int axis) {
  const float c = prim.lo[axis] + prim.hi[axis];
  return c == c ? c : 0.0f;
}

// Boxes of the binning, lanes x, y, z (lane 3 unused).
struct Bounds {
  F4 lo = F4::splat(kInf), hi = F4::splat(-kInf);
  void extend(const Bounds& b) {
    lo = simd::min(lo, b.lo);
    hi = simd::max(hi, b.hi);
  }
  void extend(F4 l, F4 h) {
    lo = simd::min(lo, l);
    hi = simd::max(hi, h);
  }
  Box box() const {
    float l[4], h[4];
    simd::store(l, lo);
    simd::store(h, hi);
    Box b;
    std::copy(l, l + 3, b.lo);
    std::copy(h, h + 3, b.hi);
    return b;
  }
};

// The bits of f as an integer of the same order (f not NaN; -0 and +0 equal).
std::uint32_t sortable_bits(float f) {
  f += 0.0f;  // -0 becomes +0
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  return (bits & 0x80000000u) != 0 ? ~bits : bits | 0x80000000u;
}

// Where a mesh stores its faces in no spatial order, binned SAH is slow: consecutive faces fall
// in different bins, so the binning by runs does not apply and each face's bin is a load and a
// store of its box (buildings.ply, 400k faces: 18 face visits per face of the binning, 3.6 of
// them in runs; torus1m, stored in grid order: 15.5 and 12.8; the splits took 44-46 ms against
// 72-74 ms for 2.5 times the faces). Such meshes are sorted along a Morton curve instead, and
// every range of more than kAlignBelow faces is split where the highest bit in which its codes
// differ changes (Lauterbach et al., "Fast BVH construction on GPUs", 2009: the LBVH), its box
// the union of its children's; smaller ranges keep the exact SAH over full blocks of 4 below.
// No pass over a range is needed to split it, so the splits took 14-15 ms on buildings.ply,
// the sort 11 ms (codes and three 10-bit radix passes on the team, then the records moved);
// queries in such trees were within 3 % of the SAH tree's (docs/performance-log.md §3, thirteenth
// session). Coherent orders keep binned SAH, which then costs about what the sort and the
// Morton splits cost together and gives trees 2-3 % faster to query (torus100k -> torus1m).

// True where more than a quarter of the probed pairs of consecutive faces have centres in
// different cells of a 16^3 grid over the centres' box: 0.04 for torus1m (a grid's rows), 0.13
// torus100k, 0.49 buildings.ply, 0.68 bunny00, 0.93 armadillo, 1.0 torus1m with its faces
// shuffled. O(n / 64).
bool out_of_spatial_order(const Prim* prims, std::uint32_t n, const Box& centres) {
  auto cell = [&centres](const Prim& prim, int k) {
    const double extent = double(centres.hi[k]) - centres.lo[k];
    const double t =
        extent > 0.0 ? (centre_key(prim, k) - centres.lo[k]) / extent * kOrderGrid : 0.0;
    return t >= kOrderGrid - 1 ? kOrderGrid - 1 : t > 0.0 ? static_cast<int>(t) : 0;  // NaN: 0
  };
  std::uint32_t pairs = 0, apart = 0;
  for (std::uint32_t i = 0; i + 1 < n; i += kOrderProbeStride, ++pairs)
    for (int k = 0; k < 3; ++k)
      if (cell(prims[i], k) != cell(prims[i + 1], k)) {
        ++apart;
        break;
      }
  return 4 * apart > pairs;
}

// Sorts prims[0, n) along a Morton curve of 2^10 cells per axis on a cubic grid over `centres`
// (the box of the records' centres), and gives each position's 30-bit code in codes[0, n). A
// stable LSD radix sort of (code, position) keys: three passes of 10 bits, each thread counting
// and scattering its own range (offsets bucket-major, thread-minor, so equal digits keep their
// order and the result is the same for any team). O(n).
void sort_along_morton_curve(std::unique_ptr<Prim[]>& prims, std::uint32_t n, const Box& centres,
                             int team, std::vector<std::uint32_t>& codes) {
  constexpr std::uint32_t kRadix = 1u << kMortonBits;
  constexpr float kMaxCell = static_cast<float>(kRadix - 1);
  float extent = 0.0f;
  for (int k = 0; k < 3; ++k) extent = std::max(extent, centres.hi[k] - centres.lo[k]);
  const float scale = extent > 0.0f && extent < kInf ? 0.999f * kRadix / extent : 0.0f;
  std::unique_ptr<std::uint64_t[]> keys(new std::uint64_t[n]), other(new std::uint64_t[n]);
  std::vector<std::uint32_t> offsets(static_cast<std::size_t>(team) * kRadix);
  const auto& spread = detail::kMortonSpread.bits;  // 7 bits to every third (metric/morton_order.h)
#pragma omp parallel num_threads(team)
  {
    const auto me = static_cast<std::uint32_t>(omp_get_thread_num());
    const auto size = static_cast<std::uint32_t>(omp_get_num_threads());
    const auto begin = static_cast<std::uint32_t>(std::uint64_t{n} * me / size);
    const auto end = static_cast<std::uint32_t>(std::uint64_t{n} * (me + 1) / size);
    for (std::uint32_t i = begin; i < end; ++i) {
      std::uint64_t code = 0;
      for (int k = 0; k < 3; ++k) {
        const float t = (centre_key(prims[i], k) - centres.lo[k]) * scale;
        const auto c = static_cast<std::uint32_t>(t > 0.0f ? (t < kMaxCell ? t : kMaxCell) : 0.0f);
        code |= (spread[c & 127u] | spread[c >> 7] << 21) << k;
      }
      keys[i] = code << 32 | i;
    }
    std::uint64_t* from = keys.get();
    std::uint64_t* to = other.get();
    std::uint32_t* mine = offsets.data() + std::size_t{me} * kRadix;
    for (int pass = 0; pass < 3; ++pass) {
      const int shift = 32 + kMortonBits * pass;
      std::fill(mine, mine + kRadix, 0u);
      for (std::uint32_t i = begin; i < end; ++i) ++mine[(from[i] >> shift) & (kRadix - 1)];
#pragma omp barrier
#pragma omp single
      {
        std::uint32_t sum = 0;
        for (std::uint32_t d = 0; d < kRadix; ++d)
          for (std::uint32_t t = 0; t < size; ++t)
            sum += std::exchange(offsets[std::size_t{t} * kRadix + d], sum);
      }  // (the single's barrier: every thread's offsets are ready)
      for (std::uint32_t i = begin; i < end; ++i)
        to[mine[(from[i] >> shift) & (kRadix - 1)]++] = from[i];
#pragma omp barrier
      std::swap(from, to);
    }
  }
  keys.swap(other);  // three passes: the sorted keys are in `other`
  other.reset();
  std::unique_ptr<Prim[]> sorted(new Prim[n]);
  codes.resize(n);
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for num_threads(team) schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    sorted[i] = prims[static_cast<std::uint32_t>(keys[i])];
    codes[i] = static_cast<std::uint32_t>(keys[i] >> 32);
  }
  prims.swap(sorted);
}

// Trivial (no initialisers): 2F of them are allocated up front and only those used are ever
// written, so the unused part of the allocation is never touched.
struct BinaryNode {
  float lo[3], hi[3];
  std::uint32_t index;  // inner: first of two consecutive children; leaf: first slot in prims
  // Leaf: 1 .. kLeafSize faces. Inner: 0 until its children are built, then its collapse plan
  // (metric/wide_collapse.h, kCollapsePlanned set).
  std::uint32_t count;
  bool leaf() const { return count - 1 < kLeafSize; }
  void set_box(const Box& b) {
    std::copy(b.lo, b.lo + 3, lo);
    std::copy(b.hi, b.hi + 3, hi);
  }
  double half_area() const {
    const double dx = double(hi[0]) - lo[0], dy = double(hi[1]) - lo[1], dz = double(hi[2]) - lo[2];
    return dx * dy + dy * dz + dz * dx;
  }
};

// Squared distances from p to four boxes (float frame): box_gap2 of the box [p, p].
inline F4 box_sq_distances_f4(const F4 lo[3], const F4 hi[3], const F4 p[3]) {
  return box_gap2(lo, hi, p, p);
}
// The same for the four boxes of a node.
inline F4 box_sq_distances(const float lo[3][4], const float hi[3][4], const F4 p[3]) {
  const F4 l[3] = {F4::load(lo[0]), F4::load(lo[1]), F4::load(lo[2])};
  const F4 h[3] = {F4::load(hi[0]), F4::load(hi[1]), F4::load(hi[2])};
  return box_sq_distances_f4(l, h, p);
}

inline F4 dot3(const F4 a[3], const F4 b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline void cross3(const F4 a[3], const F4 b[3], F4 out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

// Appends query i's answer (its distance and ties) to a batch's flattened results.
inline void append_answer(BatchHits& out, std::size_t i, double distance,
                          const std::vector<SurfaceHit>& ties) {
  out.distance[i] = distance;
  if (ties.size() == 1)  // the common case, without the range insertion's call
    out.hits.push_back(ties.front());
  else
    out.hits.insert(out.hits.end(), ties.begin(), ties.end());
  out.first[i + 1] = static_cast<std::uint32_t>(out.hits.size());
}

// A number for each index built in this process, never reused (the plane caches' owner).
std::uint64_t next_id() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

}  // namespace

namespace detail {

// The build's first step, before the evaluator (TriangleBvh's delegating constructor): the float
// frame and the face records.
struct FaceRecords {
  std::unique_ptr<FaceBox[]> prims;  // one per face, in face order
  LaneBounds boxes, centres;         // their boxes' and (twice) their centres' bounds
  BoundingBox corner_box;            // of the referenced vertices (corner_bounding_box)
  BoundingBox position_box;          // of all vertices (position_bounding_box)
  FrameMap frame;                    // centred on corner_box, its largest half extent scaled to 1
  bool cull_scale = true;            // the frame's extent within [kMinExtent, kMaxExtent]
};

}  // namespace detail

namespace {

// A mesh as the raw arrays the face records and leaf blocks read (3 doubles per vertex, 3 vertex
// indices per face), and whether the CPU runs their AVX2 versions. Precondition: m has faces.
struct RawMesh {
  const double* positions;
  const std::uint32_t* corners;
  bool avx2;
};
RawMesh raw_mesh(const TriMesh& m) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Triangle) == 3 * sizeof(std::uint32_t),
                "the face records and leaf blocks read positions and faces as raw arrays");
#if defined(MESHDEV_X86_KERNELS)
  const bool avx2 = simd_level() != SimdLevel::kBaseline;
#else
  const bool avx2 = false;
#endif
  return {&m.positions[0].x, m.faces[0].data(), avx2};
}

// The float frame of a box: centred on it, the largest half extent scaled to 1. Squared
// distances in double underflow (or overflow) for meshes this small (or large), so faces far
// apart in the frame can tie at a squared distance of 0 (or infinity) in the oracle's
// arithmetic: such meshes are searched without culling (cull = false).
void set_frame(const BoundingBox& bbox, detail::FrameMap& frame, bool& cull) {
  const Vec3 origin = 0.5 * (bbox.min + bbox.max);
  const Vec3 half = 0.5 * (bbox.max - bbox.min);
  const double extent = std::max({half.x, half.y, half.z});
  frame = {{origin.x, origin.y, origin.z},
           extent > 0.0 && std::isfinite(1.0 / extent) ? 1.0 / extent : 1.0};
  cull = extent >= kMinExtent && extent <= kMaxExtent;
}

// The face records of `m` on `threads` OpenMP threads (0: the default). They are made in the
// frame of the box of all vertices (read in order, 0.3 ms for torus1m on 2 threads); the records
// pass, which reads every face's corners anyway, gives the box of the referenced vertices, which
// the frame is defined by. Where the two boxes differ (a vertex no face uses lies outside the
// others), the records are made again in the second one's frame. That box took a pass of its own
// through the faces before (corner_bounding_box, 2.0 ms of torus1m's 70 ms build on 2 threads):
// builds now 2-3 % faster (torus1m on 1 and 2 threads, buildings.ply on 2; the least of 15
// builds in each of 3-5 alternating processes, docs/performance-log.md §3). Precondition: m has
// faces. O(F / threads).
detail::FaceRecords face_records(const TriMesh& m, int threads) {
  const auto n = static_cast<std::uint32_t>(m.faces.size());
  assert(n > 0);
  const int team = threads > 0 ? threads : omp_get_max_threads();
  const RawMesh raw = raw_mesh(m);
  const double* const positions = raw.positions;
  const std::uint32_t* const corners = raw.corners;
  const bool avx2 = raw.avx2;
  detail::FaceRecords r;
  r.position_box = position_bounding_box(m, team);
  // Allocated uninitialised and first written by the threads that use it.
  r.prims.reset(new Prim[n]);
  std::vector<detail::LaneBounds> part_boxes(static_cast<std::size_t>(team)),
      part_centres(part_boxes);
  std::vector<detail::CornerBounds> part_corners(static_cast<std::size_t>(team));
  // The face records four at a time in AVX2 lanes where the CPU has them (metric/face_boxes.h:
  // torus1m's build 1.088 / 1.081 faster on 1 / 2 threads, torus1m_shuffled 1.095 / 1.117,
  // buildings 1.126 / 1.081; `peer_compare A B 1000000 --ab 6 --ab-build`, docs/performance-log.md
  // §3), each thread its share of the faces in order; their bounds merged (min and max: the same
  // for any team).
  auto make = [&](const BoundingBox& box) {
    set_frame(box, r.frame, r.cull_scale);
#pragma omp parallel num_threads(team)
    {
      const auto t = static_cast<std::size_t>(omp_get_thread_num());
      const auto members = static_cast<std::size_t>(omp_get_num_threads());
      const auto from = static_cast<std::uint32_t>(n * t / members);
      const auto to = static_cast<std::uint32_t>(n * (t + 1) / members);
      part_boxes[t] = part_centres[t] = detail::LaneBounds{};
      part_corners[t] = detail::CornerBounds{};
      if (avx2)
        detail::face_boxes_avx2(positions, corners, from, to, r.frame, r.prims.get() + from,
                                part_boxes[t], part_centres[t], part_corners[t]);
      else
        detail::face_boxes(positions, corners, from, to, r.frame, r.prims.get() + from,
                           part_boxes[t], part_centres[t], part_corners[t]);
    }
    Bounds boxes, centres;
    BoundingBox corner_box;
    for (std::size_t t = 0; t < part_boxes.size(); ++t) {
      boxes.extend(F4::load(part_boxes[t].lo), F4::load(part_boxes[t].hi));
      centres.extend(F4::load(part_centres[t].lo), F4::load(part_centres[t].hi));
      for (int k = 0; k < 3; ++k) {  // (an empty share holds +inf and -inf: it changes nothing)
        if (part_corners[t].lo[k] < corner_box.min[k]) corner_box.min[k] = part_corners[t].lo[k];
        if (part_corners[t].hi[k] > corner_box.max[k]) corner_box.max[k] = part_corners[t].hi[k];
      }
    }
    simd::store(r.boxes.lo, boxes.lo);
    simd::store(r.boxes.hi, boxes.hi);
    simd::store(r.centres.lo, centres.lo);
    simd::store(r.centres.hi, centres.hi);
    return corner_box;
  };
  r.corner_box = make(r.position_box);
  if (!(r.corner_box.min == r.position_box.min && r.corner_box.max == r.position_box.max))
    make(r.corner_box);
  return r;
}

}  // namespace

TriangleBvh::TriangleBvh(const TriMesh& target, const TieOptions& ties, int threads)
    : TriangleBvh(target, ties, threads, face_records(target, threads)) {}

TriangleBvh::TriangleBvh(const TriMesh& target, const TieOptions& ties, int threads,
                         detail::FaceRecords&& records)
    : eval_(target, ties, records.corner_box, records.position_box, /*with_spheres=*/false),
      kernels_(&plane_kernels(simd_level())),
      avx_gather_(simd_level() != SimdLevel::kBaseline),
      id_(next_id()),
      check_reach_(std::sqrt(eval_.exact_check_sq)) {
  build(threads, records);
}

std::size_t TriangleBvh::memory_bytes() const {
  return nodes_.size() * sizeof(Node) + leaves_.size() * sizeof(Leaf);
}

void TriangleBvh::build(int threads, detail::FaceRecords& records) {
  const TriMesh& m = *eval_.mesh;
  const auto n = static_cast<std::uint32_t>(m.faces.size());
  const detail::FrameMap& frame_map = records.frame;
  frame_ = frame_map;
  cull_scale_ = records.cull_scale;
  const int team = threads > 0 ? threads : omp_get_max_threads();
  // A vertex in the float frame (in double) is computed where it is read (the face records, the
  // leaf blocks): a stored copy of the frame was 24 bytes per vertex written in a pass of its own
  // (torus1m: 12 MB; the same trees, docs/performance-log.md §3, twenty-seventh session).
  // Scratch arrays are allocated uninitialised and first written by the threads that use them.

  // Binary SAH tree over the face boxes (float frame).
  std::unique_ptr<Prim[]>& prims = records.prims;
  // The bin of the face at a position while its range is split; once a leaf is made of a range,
  // 1 at the range's first position and 0 at the others (every position is in one leaf, so after
  // the splits it marks where the leaves start, in the order of the face records).
  std::unique_ptr<std::uint8_t[]> bin_at(new std::uint8_t[n]);
  const RawMesh raw = raw_mesh(m);
  const double* const positions = raw.positions;
  const std::uint32_t* const corners = raw.corners;
  const bool avx2 = raw.avx2;
  Bounds root_bounds, root_centres;
  root_bounds.extend(F4::load(records.boxes.lo), F4::load(records.boxes.hi));
  root_centres.extend(F4::load(records.centres.lo), F4::load(records.centres.hi));
  std::vector<std::uint32_t> codes;  // with morton_splits_: each position's Morton code
  morton_splits_ = n >= kMortonFrom && out_of_spatial_order(prims.get(), n, root_centres.box());
  if (morton_splits_) sort_along_morton_curve(prims, n, root_centres.box(), team, codes);
  // The binary tree has at most 2n - 1 nodes; children are allocated in pairs, so subtrees can
  // be built in parallel (OpenMP tasks above kTaskBelow faces): above kTaskBelow faces from a
  // shared counter; a subtree of at most kTaskBelow faces, which one thread builds, from that
  // thread's `Cursor`, a run of kCursorIds ids taken from the shared counter at a time, so its
  // nodes lie together in memory. From the shared counter alone, the two threads' nodes
  // alternated, two to a cache line: the threads wrote each other's lines (torus1m's splits took
  // 81 ms on 2 threads instead of 60) and the collapse read twice the lines. The ids handed out
  // are dense (a thread's last run at most unused), so the tree's written memory is one prefix of
  // its storage, which the leaf blocks then take over (below); before, each such subtree took 2c
  // ids at once for its c faces and wrote about c / 2 of them (2 blocks - 1 nodes, blocks
  // of 3.7-3.9 faces). The tree's shape does not depend on the thread count: each split depends
  // only on its own range of faces.
  constexpr std::uint32_t kCursorIds = 4096;  // 128 KB of nodes
  struct alignas(64) Cursor {                 // a thread's own line: no false sharing
    std::uint32_t next = 0, end = 0;          // its run of ids
    std::uint32_t taken = 0;                  // ids it handed out
  };
  std::vector<Cursor> cursors(static_cast<std::size_t>(team));
  const std::size_t max_nodes =
      2 * static_cast<std::size_t>(n) + static_cast<std::size_t>(team) * kCursorIds + 2;
  RawArray<BinaryNode> tree(max_nodes);  // its storage then holds the leaf blocks (below)
  std::atomic<std::uint32_t> next_node{1};
  std::atomic<std::uint32_t> used_nodes{1};
  auto split = [&](auto&& self, std::uint32_t node, std::uint32_t begin, std::uint32_t end,
                   int depth, bool known, Bounds bounds, Bounds centre_bounds, bool long_runs,
                   int sorted_axis, Cursor* pool) -> detail::CollapseCosts {
    assert(depth <= kMaxBinaryDepth);
    Prim* const first = prims.get();
    // A Morton split needs no pass over the range: the node's box is its children's, set after
    // them.
    const bool by_code = morton_splits_ && end - begin > kAlignBelow && depth < kMaxSahDepth;
    if (!known && !by_code)
      for (std::uint32_t i = begin; i < end; ++i) {
        bounds.extend(F4::load(first[i].lo), F4::load(first[i].hi));
        const F4 c = centre2(first[i]);
        centre_bounds.extend(c, c);
      }
    if (!by_code) tree[node].set_box(bounds.box());
    const std::uint32_t count = end - begin;
    if (count <= kLeafSize) {
      tree[node].index = begin;
      tree[node].count = count;
      for (std::uint32_t i = begin; i < end; ++i) bin_at[i] = i == begin;
      return {};
    }
    const Box centres = centre_bounds.box();
    int axis = 0;
    double axis_extent = -1.0;
    for (int k = 0; k < 3; ++k) {
      const double e = double(centres.hi[k]) - centres.lo[k];
      if (e > axis_extent) {
        axis_extent = e;
        axis = k;
      }
    }
    // Equal centres or too deep: split the list in halves, which bounds depth and leaf sizes.
    std::uint32_t mid = begin + std::max(kLeafSize, count / 2 / kLeafSize * kLeafSize);
    bool children_known = false;
    bool children_long_runs = long_runs;
    int children_sorted_axis = -1;  // the axis the children's faces are sorted along, if one
    Bounds child_bounds[2], child_centres[2];
    if (by_code) {
      // Where the highest bit in which the range's codes differ turns from 0 to 1 (the codes are
      // sorted, so it lies strictly inside); equal codes: the halves above.
      const std::uint32_t c0 = codes[begin], c1 = codes[end - 1];
      if (c0 != c1) {
        const int bit = 31 - __builtin_clz(c0 ^ c1);
        mid = static_cast<std::uint32_t>(
            std::partition_point(codes.begin() + begin, codes.begin() + end,
                                 [bit](std::uint32_t c) { return (c >> bit & 1u) == 0; }) -
            codes.begin());
      }
    } else if (count <= kAlignBelow && axis_extent > 0.0 && depth < kMaxSahDepth) {
      // Small subtrees: sorted along the axis, and split where SAH is least among the splits
      // whose left side is a multiple of 4 faces (costed exactly, from prefix and suffix boxes).
      // Leaves are then full blocks of 4 except about one per subtree of kAlignBelow faces,
      // which keeps the structure near 55 bytes per face instead of about 77 (SAH alone leaves
      // blocks 2/3 full).
      // Ordered by key, then face, as 64-bit integers (key bits above the face's), all distinct:
      // each face goes straight to its rank, the number of smaller keys (at most 32 x 32
      // comparisons without a branch, four per instruction where the CPU runs AVX2,
      // metric/key_ranks.h: torus1m's build 1.036 / 1.027 on 1 / 2 threads, `peer_compare
      // torus100k.ply torus1m.ply 1000000 --ab 8 --ab-build`; docs/performance-log.md §3).
      // std::sort of (key, position) pairs and a move by the sorted positions gave the same order
      // with a branch per comparison, on keys in no order a predictor learns: builds 6-10 % slower
      // (peer_compare --ab 9 --ab-build, 1 / 2 threads: torus1m 1.059 / 1.069, buildings.ply 1.087
      // / 1.100, torus1m_shuffled 1.086 / 1.063; docs/performance-log.md §3, thirty-third session).
      // Sorting the 32-byte faces by their keys took twice as long.
      // Children of such a split along the same axis are sorted already (a range of the order
      // by key, then face): their sort is skipped (torus1m's build 1.009 / 1.010 on 1 / 2 threads,
      // buildings.ply 1.045 / 1.049; the same trees; `peer_compare A B 1000000 --ab 8
      // --ab-build`, docs/performance-log.md §3).
      if (sorted_axis != axis) {
        std::uint64_t key[kAlignBelow];
        Prim moved[kAlignBelow];
        for (std::uint32_t i = 0; i < count; ++i) {
          const Prim& prim = first[begin + i];
          key[i] = std::uint64_t{sortable_bits(centre_key(prim, axis))} << 32 | face_of(prim);
          moved[i] = prim;
        }
        static_assert(kAlignBelow <= detail::kMaxRankKeys, "a small subtree's keys fit key_ranks");
        std::uint32_t rank[kAlignBelow];
        if (avx2)
          detail::key_ranks_avx2(key, count, rank);
        else
          detail::key_ranks(key, count, rank);
        for (std::uint32_t i = 0; i < count; ++i) first[begin + rank[i]] = moved[i];
      }
      children_sorted_axis = axis;
      constexpr std::uint32_t kCuts = kAlignBelow / kLeafSize + 1;
      Bounds prefix[kCuts], prefix_centres[kCuts], suffix[kCuts], suffix_centres[kCuts];
      Bounds acc, acc_centres;
      for (std::uint32_t i = 0; i < count; ++i) {  // prefix[c]: the first 4c faces
        if (i % kLeafSize == 0)
          prefix[i / kLeafSize] = acc, prefix_centres[i / kLeafSize] = acc_centres;
        const Prim& prim = first[begin + i];
        acc.extend(F4::load(prim.lo), F4::load(prim.hi));
        const F4 c = centre2(prim);
        acc_centres.extend(c, c);
      }
      acc = acc_centres = Bounds{};
      const std::uint32_t last_cut = (count - 1) / kLeafSize;  // right side never empty
      for (std::uint32_t i = count; i-- > kLeafSize;) {        // suffix[c]: the faces from 4c on
        const Prim& prim = first[begin + i];
        acc.extend(F4::load(prim.lo), F4::load(prim.hi));
        const F4 c = centre2(prim);
        acc_centres.extend(c, c);
        if (i % kLeafSize == 0 && i / kLeafSize <= last_cut)
          suffix[i / kLeafSize] = acc, suffix_centres[i / kLeafSize] = acc_centres;
      }
      std::uint32_t best = 1;
      double best_cost = std::numeric_limits<double>::infinity();
      for (std::uint32_t cut = 1; cut <= last_cut; ++cut) {
        const double cost = prefix[cut].box().half_area() * (cut * kLeafSize) +
                            suffix[cut].box().half_area() * (count - cut * kLeafSize);
        if (cost < best_cost) {
          best_cost = cost;
          best = cut;
        }
      }
      mid = begin + best * kLeafSize;
      child_bounds[0] = prefix[best], child_centres[0] = prefix_centres[best];
      child_bounds[1] = suffix[best], child_centres[1] = suffix_centres[best];
      children_known = true;
    } else if (axis_extent > 0.0 && depth < kMaxSahDepth) {
      Bounds bin_box[kBins], bin_centres[kBins];
      std::uint32_t bin_count[kBins] = {};
      const double lo = centres.lo[axis];
      const double scale = kBins / axis_extent;  // finite: axis_extent >= the least float
      // The faces' bins first, in a pass of their own (metric/centre_bins.h), four faces per
      // step where the CPU runs AVX2, the same trees: torus1m's build 1.085-1.100 / 1.061-1.062
      // faster on 1 / 2 threads than the bins computed face by face inside the loops below, and
      // 1.072 / 1.086 (torus100k 1.102 / 1.087) than the same pass in scalar code (`peer_compare
      // A B 1000000 --ab 8 --ab-build`, docs/performance-log.md §3). Meshes built by Morton
      // splits bin no faces.
      // Faces near in the mesh's order are often near in space and fall in the bin of the face
      // before. Where the parent's faces did so in runs of kMinRun or more on average (and at
      // the root), runs are gathered in registers and added to their bin once, instead of a load
      // and a store per face and box; where they did not, that branch would be mispredicted too
      // often, and each face goes to its bin. The bins are the same either way (min and max).
      std::uint8_t* const bins = bin_at.get();
      if (avx2)
        detail::centre_bins_avx2(first + begin, count, axis, lo, scale, kBins, bins + begin);
      else
        detail::centre_bins(first + begin, count, axis, lo, scale, kBins, bins + begin);
      int run = bins[begin];
      std::uint32_t changes = 0;  // faces in another bin than the face before
      if (long_runs) {
        Bounds run_box, run_centres;
        std::uint32_t run_count = 0;
        for (std::uint32_t i = begin; i < end; ++i) {
          const int b = bins[i];
          if (b != run) {
            bin_box[run].extend(run_box);
            bin_centres[run].extend(run_centres);
            bin_count[run] += run_count;
            run = b;
            run_box = run_centres = Bounds{};
            run_count = 0;
            ++changes;
          }
          const F4 lo4 = F4::load(first[i].lo), hi4 = F4::load(first[i].hi);
          run_box.extend(lo4, hi4);
          const F4 c = lo4 + hi4;
          run_centres.extend(c, c);
          ++run_count;
        }
        bin_box[run].extend(run_box);
        bin_centres[run].extend(run_centres);
        bin_count[run] += run_count;
      } else {
        for (std::uint32_t i = begin; i < end; ++i) {
          const int b = bins[i];
          changes += b != run;
          run = b;
          const F4 lo4 = F4::load(first[i].lo), hi4 = F4::load(first[i].hi);
          bin_box[b].extend(lo4, hi4);
          const F4 c = lo4 + hi4;
          bin_centres[b].extend(c, c);
          ++bin_count[b];
        }
      }
      children_long_runs = changes * kMinRun <= count;
      double right_area[kBins];
      std::uint32_t right_count[kBins];
      Bounds acc;
      std::uint32_t acc_count = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.extend(bin_box[b]);
        acc_count += bin_count[b];
        right_area[b] = acc.box().half_area();
        right_count[b] = acc_count;
      }
      Bounds left;
      std::uint32_t left_count = 0;
      double best_cost = std::numeric_limits<double>::infinity();
      int best_split = -1;
      for (int b = 1; b < kBins; ++b) {
        left.extend(bin_box[b - 1]);
        left_count += bin_count[b - 1];
        if (left_count == 0 || right_count[b] == 0) continue;
        const double cost = left.box().half_area() * left_count + right_area[b] * right_count[b];
        if (cost < best_cost) {
          best_cost = cost;
          best_split = b;
        }
      }
      if (best_split > 0) {
        // Hoare partition by the bins just computed: each position's bin is read before any
        // swap moves another face there.
        std::uint32_t i = begin, j = end;
        for (;;) {
          while (i < j && bin_at[i] < best_split) ++i;
          while (i < j && bin_at[j - 1] >= best_split) --j;
          if (i >= j) break;  // (i < j here means bin_at[i] >= best_split > bin_at[j - 1])
          std::swap(first[i++], first[--j]);
        }
        mid = i;
        for (int b = 0; b < kBins; ++b) {
          child_bounds[b < best_split ? 0 : 1].extend(bin_box[b]);
          child_centres[b < best_split ? 0 : 1].extend(bin_centres[b]);
        }
        children_known = true;
      }
    }
    if (pool == nullptr && count <= kTaskBelow)
      pool = &cursors[static_cast<std::size_t>(omp_get_thread_num())];
    std::uint32_t left_child;
    if (pool != nullptr) {
      if (pool->next == pool->end) {
        pool->next = next_node.fetch_add(kCursorIds);
        pool->end = pool->next + kCursorIds;
      }
      left_child = pool->next;
      pool->next += 2;
      pool->taken += 2;
    } else {
      left_child = next_node.fetch_add(2);
      used_nodes.fetch_add(2);
    }
    assert(left_child + 1 < max_nodes);
    tree[node].index = left_child;
    tree[node].count = 0;
    detail::CollapseCosts costs[2];  // the children's, for the collapse's plan
    if (count > kTaskBelow) {
#pragma omp task default(shared) firstprivate(left_child, mid, children_known, children_long_runs)
      costs[0] = self(self, left_child, begin, mid, depth + 1, children_known, child_bounds[0],
                      child_centres[0], children_long_runs, -1, nullptr);
      costs[1] = self(self, left_child + 1, mid, end, depth + 1, children_known, child_bounds[1],
                      child_centres[1], children_long_runs, -1, nullptr);
#pragma omp taskwait
    } else {
      costs[0] = self(self, left_child, begin, mid, depth + 1, children_known, child_bounds[0],
                      child_centres[0], children_long_runs, children_sorted_axis, pool);
      costs[1] = self(self, left_child + 1, mid, end, depth + 1, children_known, child_bounds[1],
                      child_centres[1], children_long_runs, children_sorted_axis, pool);
    }
    if (by_code) {
      const BinaryNode &l = tree[left_child], &r = tree[left_child + 1];
      for (int k = 0; k < 3; ++k) {
        tree[node].lo[k] = std::min(l.lo[k], r.lo[k]);
        tree[node].hi[k] = std::max(l.hi[k], r.hi[k]);
      }
    }
    detail::CollapseCosts out;
    tree[node].count = detail::collapse_plan(tree[node].half_area(), costs[0], costs[1], out);
    return out;
  };
#pragma omp parallel num_threads(team)
#pragma omp single
  split(split, 0, 0, n, 1, true, root_bounds, root_centres, true, -1, nullptr);
  for (const Cursor& cursor : cursors) used_nodes += cursor.taken;
  // The tree's nodes lie in ids [0, written_nodes): its storage's only bytes written so far.
  const std::size_t written_nodes = next_node.load();
  assert(used_nodes.load() <= written_nodes && written_nodes <= max_nodes);

  // The leaf blocks in the order of the face records: block l holds the faces at positions
  // leaf_first[l] .. leaf_first[l + 1] - 1 (leaf_first[blocks] = n). The collapse below keeps
  // each node's children in that order, so it numbers the blocks the same way (depth first), and
  // the blocks need not wait for it.
  std::vector<std::uint32_t> leaf_first;
  {
    std::vector<std::uint32_t> starts(static_cast<std::size_t>(team) + 1, 0);
#pragma omp parallel num_threads(team)
    {
      const auto t = static_cast<std::size_t>(omp_get_thread_num());
      const auto members = static_cast<std::size_t>(omp_get_num_threads());
      const std::size_t from = n * t / members, to = n * (t + 1) / members;
      std::uint32_t own = 0;
      for (std::size_t i = from; i < to; ++i) own += bin_at[i];
      starts[t + 1] = own;
#pragma omp barrier
#pragma omp single
      {
        for (std::size_t k = 1; k <= members; ++k) starts[k] += starts[k - 1];
        leaf_first.resize(starts[members] + 1);
        leaf_first[starts[members]] = n;
      }
      std::uint32_t at = starts[t];
      for (std::size_t i = from; i < to; ++i)
        if (bin_at[i] != 0) leaf_first[at++] = static_cast<std::uint32_t>(i);
    }
  }
  const std::size_t blocks = leaf_first.size() - 1;

  // Collapse into 4-wide nodes (recursive: the binary depth is bounded) by the plans the splits
  // made (metric/wide_collapse.h: the least summed half area of the wide nodes), on one thread
  // (the others touch the pages the leaf blocks will fill that nothing has written yet, below),
  // then the leaf blocks on the whole
  // team. Beside the leaf blocks, which read their corners by loads since the forty-fifth
  // session, the collapse took 11.5 ms instead of 5.0 (torus1m, 2 threads; the two phases 14.5
  // ms against 11.7): builds 1.061 faster on torus1m, 1.27 on buildings.ply (medians of 30
  // alternating builds in one process, docs/performance-log.md §3). The greedy collapse it
  // replaced (the inner child of largest area opened until a node had 4 children) left nodes of
  // 2 leaves under most nodes of small subtrees: torus1m 126,627 nodes, now 107,485 (60.5 -> 58.4
  // bytes per face), its queries from torus100k 1.0045-1.0062 / 1.0060-1.0151 faster on 1 / 2
  // threads, the builds and other pairs within noise (`peer_compare A B 1000000 --ab 8
  // --ab-build`, docs/performance-log.md §3).
  nodes_.clear();
  leaves_ = RawArray<Leaf>();
  nodes_.reserve(used_nodes.load() / 3 + 1);
  std::uint32_t next_block = 0;  // blocks numbered so far, depth first
  depth_ = 0;
  // A binary node's children and collapse plan, for metric/wide_collapse.h's walks.
  auto inner = [&](std::uint32_t bi, std::uint32_t& left, std::uint32_t& right,
                   std::uint32_t& plan) {
    if (tree[bi].leaf()) return false;
    left = tree[bi].index, right = tree[bi].index + 1, plan = tree[bi].count;
    return true;
  };
  auto collapse = [&](auto&& self, std::uint32_t bi, int depth) -> std::uint32_t {
    depth_ = std::max(depth_, depth);
    if (tree[bi].leaf()) {
      assert(next_block < blocks && leaf_first[next_block] == tree[bi].index);
      return kLeafBit | next_block++;
    }
    assert(tree[bi].count & detail::kCollapsePlanned);
    std::uint32_t kids[4] = {0, 0, 0, 0};
    int count = 0;
    detail::for_each_wide_child(inner, bi, [&](std::uint32_t kid) { kids[count++] = kid; });
    assert(count >= 2 && count <= 4);
    const auto id = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    std::uint32_t refs[4] = {kEmpty, kEmpty, kEmpty, kEmpty};
    for (int k = 0; k < count; ++k) refs[k] = self(self, kids[k], depth + 1);
    Node& node = nodes_[id];  // after the recursion: emplace_back may have reallocated
    for (int k = 0; k < 4; ++k) {
      node.child[k] = refs[k];
      for (int axis = 0; axis < 3; ++axis) {
        node.lo[axis][k] = k < count ? tree[kids[k]].lo[axis] : kInf;
        node.hi[axis][k] = k < count ? tree[kids[k]].hi[axis] : -kInf;
      }
    }
    return id;
  };

  // Leaf blocks: float corners (round to nearest), the measured rounding, the cull margins; in
  // AVX2 lanes where the CPU has them (metric/leaf_blocks.h: torus1m's build 1.022 / 1.060 on 1 /
  // 2 threads, torus1m_shuffled 1.044 / 1.030, and 1.087 / 1.091 more once each corner came by
  // one load instead of a gather per axis, docs/performance-log.md §3).
  const auto leaf_count = static_cast<std::int64_t>(blocks);
  // The blocks go into the binary tree's storage once the collapse has read it (where they fit:
  // 176 bytes a block against 32 a node and at least 2n nodes, so wherever the blocks hold 2.75
  // faces or more on average, as the small subtrees' splits into full blocks of 4 make them: 3.7
  // to 3.9 on the meshes of docs/performance-log.md §3, forty-eighth session), else into storage
  // of their own. The tree's written prefix (2 blocks - 1 nodes of 32 bytes: 16.8 bytes a face
  // on torus1m) is then
  // already the process's memory, and the blocks take no page faults there, nor does the process
  // hold both at once: torus1m's first build in peer_compare 16,009 -> 11,855 page faults, the
  // process's peak 364 -> 331 MiB; `meshdev compare torus100k.ply torus1m.ply` (1M Monte Carlo
  // samples) 40,750 -> 39,100 faults, peak RSS 167,300 -> 160,700 KiB. The same trees, bit for bit;
  // the builds' time the same within this host's noise (first builds old / new 1.002 over 8
  // alternating pairs of processes; docs/performance-log.md §3, forty-eighth session).
  const std::size_t block_bytes = blocks * sizeof(Leaf);
  const bool blocks_in_tree = block_bytes <= tree.size() * sizeof(BinaryNode);
  if (!blocks_in_tree) leaves_ = RawArray<Leaf>(blocks);  // each block is written in full below
  constexpr std::int64_t kBlocksPerTask = 1024;
  // Sum of the faces' longest edges per task of kBlocksPerTask blocks (each summed in leaf order
  // by the thread that fills it), so the packet extent does not depend on the thread count.
  std::vector<double> task_size(
      static_cast<std::size_t>((leaf_count + kBlocksPerTask - 1) / kBlocksPerTask));
  double corner_error2 = 0.0;  // square roots are taken once, of the maxima
  // While one thread collapses, the others touch the pages the blocks will fill and nothing has
  // written yet, in order, one byte per page (raw storage: the blocks' fill writes every byte
  // later), so that a build on pages the process does not hold yet takes their faults on threads
  // that would wait: the blocks' own storage, or the tree's beyond its written prefix, which the
  // collapse does not read. (With the blocks in storage of their own throughout, the process's
  // first torus1m build in peer_compare, 2 threads, alternating processes, the same 16,010
  // faults: means 0.1156 -> 0.1025 s and 0.1013 -> 0.0932 s in two series of 12, where faults
  // were slow; 0.0870 -> 0.0860 s in 16 where they were not; docs/performance-log.md §3.)
  constexpr std::size_t kPage = 4096, kPagesPerStep = 16;
  char* const fill_base =
      reinterpret_cast<char*>(blocks_in_tree ? static_cast<void*>(tree.data()) : leaves_.data());
  const std::size_t untouched_from = blocks_in_tree ? written_nodes * sizeof(BinaryNode) : 0;
  // Page-aligned addresses in [fill_base + untouched_from, fill_base + block_bytes).
  const std::uintptr_t touch_first =
      (reinterpret_cast<std::uintptr_t>(fill_base) + untouched_from + kPage - 1) / kPage * kPage;
  const std::uintptr_t touch_end = reinterpret_cast<std::uintptr_t>(fill_base) + block_bytes;
  const std::size_t pages =
      touch_first < touch_end ? (touch_end - touch_first + kPage - 1) / kPage : 0;
  std::atomic<bool> collapsed{false};
  std::atomic<std::size_t> next_page{0};
#pragma omp parallel num_threads(team)
  {
#pragma omp single nowait
    {
      root_ = collapse(collapse, 0, 1);
      collapsed.store(true, std::memory_order_release);
    }
    while (!collapsed.load(std::memory_order_acquire)) {
      const std::size_t first_page = next_page.fetch_add(kPagesPerStep);
      if (first_page >= pages) break;
      for (std::size_t p = first_page; p < std::min(first_page + kPagesPerStep, pages); ++p)
        reinterpret_cast<char*>(touch_first)[p * kPage] = 0;
    }
#pragma omp barrier
#pragma omp single
    if (blocks_in_tree) leaves_ = RawArray<Leaf>(std::move(tree), blocks);
    double task_sum = 0.0;  // this thread's task so far
#pragma omp for schedule(dynamic, kBlocksPerTask) reduction(max : corner_error2)
    for (std::int64_t l = 0; l < leaf_count; ++l) {
      // The faces' corners are read through two indirections, in no order the cache foresees
      // where the mesh stores its faces in no spatial order: prefetched kAhead blocks ahead
      // (face indices) and kAhead / 2 ahead (their positions).
      constexpr std::int64_t kAhead = 16;
      if (l + kAhead < leaf_count)
        for (std::uint32_t i = leaf_first[l + kAhead]; i < leaf_first[l + kAhead + 1]; ++i)
          __builtin_prefetch(&m.faces[face_of(prims[i])]);
      if (l + kAhead / 2 < leaf_count)
        for (std::uint32_t i = leaf_first[l + kAhead / 2]; i < leaf_first[l + kAhead / 2 + 1]; ++i)
          for (std::uint32_t v : m.faces[face_of(prims[i])]) __builtin_prefetch(&m.positions[v]);
      const std::uint32_t begin = leaf_first[l], count = leaf_first[l + 1] - begin;
      assert(count >= 1 && count <= kLeafSize);
      std::uint32_t face_ids[kLeafSize];
      for (std::uint32_t lane = 0; lane < count; ++lane)
        face_ids[lane] = face_of(prims[begin + lane]);
      const detail::LeafBlockSums sums =
          avx2
              ? detail::fill_leaf_block_avx2(positions, corners, face_ids, count, frame_map,
                                             leaves_[l])
              : detail::fill_leaf_block(positions, corners, face_ids, count, frame_map, leaves_[l]);
      corner_error2 = std::max(corner_error2, sums.corner_error2);
      task_sum = (l % kBlocksPerTask == 0 ? 0.0 : task_sum) + sums.edge_sum;
      if ((l + 1) % kBlocksPerTask == 0 || l + 1 == leaf_count)
        task_size[static_cast<std::size_t>(l / kBlocksPerTask)] = task_sum;
    }
  }
  assert(next_block == blocks);
  corner_error_ = std::sqrt(corner_error2);
  const double mean_edge = std::accumulate(task_size.begin(), task_size.end(), 0.0) / n;
  packet_extent_ = kPacketExtent * mean_edge;
  full_packet_extent_ = kFullPacketExtent * mean_edge;
  assert(depth_ <= kMaxBinaryDepth);
}

std::string TriangleBvh::check_structure() const {
  const std::size_t faces = eval_.mesh->faces.size();
  std::vector<std::uint8_t> seen(faces, 0);
  std::size_t found = 0;
  std::string error;
  auto fail = [&](const std::string& what) {
    if (error.empty()) error = what;
  };
  auto inside = [](float x, float lo, float hi) { return lo <= x && x <= hi; };
  // A leaf's lanes, against the box its parent holds for it (none for a root leaf).
  auto check_leaf = [&](std::uint32_t l, const float(*lo)[4], const float(*hi)[4], int k) {
    if (l >= leaves_.size()) return fail("leaf ref " + std::to_string(l) + " out of range");
    const Leaf& leaf = leaves_[l];
    if (leaf.face[0] == kNoFace) return fail("leaf " + std::to_string(l) + " holds no face");
    bool empty = false;
    for (int lane = 0; lane < 4; ++lane) {
      const std::uint32_t f = leaf.face[lane];
      const std::string at = "leaf " + std::to_string(l) + " lane " + std::to_string(lane);
      if (f == kNoFace) {
        empty = true;
        continue;
      }
      if (empty) return fail(at + ": a face after an empty lane");
      if (f >= faces) return fail(at + ": face " + std::to_string(f) + " out of range");
      if (seen[f]++ != 0) return fail(at + ": face " + std::to_string(f) + " seen twice");
      ++found;
      if (lo == nullptr) continue;
      for (int corner = 0; corner < 3; ++corner)
        for (int axis = 0; axis < 3; ++axis)
          if (!inside(leaf.corner[corner][axis][lane], lo[axis][k], hi[axis][k]))
            return fail(at + ": face " + std::to_string(f) + " outside its box");
    }
  };
  auto visit = [&](auto&& self, std::uint32_t id) -> void {
    if (id >= nodes_.size()) return fail("node ref " + std::to_string(id) + " out of range");
    const Node& node = nodes_[id];
    for (int k = 0; k < 4; ++k) {
      const std::uint32_t ref = node.child[k];
      if (ref == kEmpty) continue;
      if ((ref & kLeafBit) != 0) {
        check_leaf(ref & ~kLeafBit, node.lo, node.hi, k);
        continue;
      }
      if (ref <= id)
        return fail("node " + std::to_string(id) + " refers back to " + std::to_string(ref));
      if (ref < nodes_.size()) {
        const Node& child = nodes_[ref];
        for (int c = 0; c < 4; ++c)
          for (int axis = 0; axis < 3; ++axis)
            if (child.child[c] != kEmpty &&
                !(node.lo[axis][k] <= child.lo[axis][c] && child.hi[axis][c] <= node.hi[axis][k]))
              return fail("node " + std::to_string(ref) + " child " + std::to_string(c) +
                          " outside its parent's box");
      }
      self(self, ref);
    }
  };
  if ((root_ & kLeafBit) != 0)
    check_leaf(root_ & ~kLeafBit, nullptr, nullptr, 0);
  else
    visit(visit, root_);
  if (error.empty() && found != faces) fail(std::to_string(faces - found) + " faces in no leaf");
  return error;
}

bool TriangleBvh::to_frame(const Vec3& p, float qf[3], double& slack) const {
  const bool cull = detail::frame_query(p, frame_, corner_error_, qf, slack) && cull_scale_;
  if (!cull) slack = corner_error_;
  return cull;
}

// The state of one query's search, shared by find() and the block packets of find_batch: the
// query, its float frame, the culling radii (float frame, enlarged to cover the query's and the
// corners' rounding and the rounding of the float tests themselves, relative, far below 1e-6),
// the best squared distance so far with its squared tie limit, and the candidates kept.
struct TriangleBvh::Search {
  Search(const Vec3& point, const QueryHint& query_hint, std::vector<SurfaceHit>& out)
      : p(point), hint(query_hint), ties(out) {}
  const Vec3& p;
  const QueryHint& hint;
  std::vector<SurfaceHit>& ties;
  F4 pf[3];
  bool cull = false;
  double slack = 0;
  double floor_dist = 0;              // the identical-triangle check's reach (0 without source)
  std::uint32_t skip_face = kNoFace;  // a face already considered (find's start face)
  double best_sq = std::numeric_limits<double>::infinity();
  double limit = std::numeric_limits<double>::infinity();  // squared tie limit of best_sq
  float box_limit2 = kInf, leaf_limit = kInf;
};

[[gnu::always_inline]] inline void TriangleBvh::narrow(Search& s, double limit_dist) const {
  if (!s.cull) return;
  // A face identical to the query's source triangle counts as distance 0 however far rounding
  // put the query from it (FaceEvaluator::evaluate), so the search never narrows below the reach
  // of that check. The radii only shrink (a block packet starts them from an upper bound).
  const double r = frame_reach(limit_dist, s.floor_dist, s.slack);
  s.box_limit2 = std::min(s.box_limit2, round_up_to_float(r * r * (1.0 + 1e-5)));
  s.leaf_limit = std::min(s.leaf_limit, round_up_to_float(r * (1.0 + 1e-6)));
}

[[gnu::always_inline]] inline void TriangleBvh::consider(Search& s, std::uint32_t f) const {
  const SurfaceHit h = eval_.evaluate(s.p, f, s.hint);
  if (h.sq_distance > s.limit) return;
  if (h.sq_distance < s.best_sq) {
    s.best_sq = h.sq_distance;
    const double l = eval_.limit(std::sqrt(s.best_sq));
    s.limit = l * l;  // = eval_.limit_sq(best_sq)
    narrow(s, l);
  }
  s.ties.push_back(h);
}

// Inline: it is the inner loop of find() (a call costs some 35 instructions per leaf block there).
[[gnu::always_inline]] inline void TriangleBvh::search_leaf(const Leaf& leaf, Search& s) const {
  // Lower bound: sqrt(h^2 + max_e out_e^2) / |n|, h = n.(p - a) the plane offset and
  // out_e = m_e.(p - origin of e) the outward offset from edge e (m_e = e x n, |m_e| =
  // |e||n|), exact in the face and edge regions, below the distance near the corners.
  const F4 zero = F4::splat(0.0f);
  const F4* pf = s.pf;
  F4 a[3], b[3], c[3], ap[3], bp[3], cp[3], e0[3], e1[3], e2[3];
  for (int k = 0; k < 3; ++k) {
    a[k] = F4::load(leaf.corner[0][k]);
    b[k] = F4::load(leaf.corner[1][k]);
    c[k] = F4::load(leaf.corner[2][k]);
    ap[k] = pf[k] - a[k];
    bp[k] = pf[k] - b[k];
    cp[k] = pf[k] - c[k];
    e0[k] = b[k] - a[k];
    e1[k] = c[k] - b[k];
    e2[k] = c[k] - a[k];
  }
  F4 nrm[3], m[3];
  cross3(e0, e2, nrm);
  // Each offset is divided by its normal's length before it is squared, so the squares stay
  // near the distance's own magnitude: squaring the raw offsets (degree 6 in the triangle's
  // size) underflowed to denormals for triangles a few 1e-6 of the mesh, with errors far
  // above the margin (found by fuzz_nearest_point).
  const F4 n_len = sqrt(dot3(nrm, nrm));
  const F4 h = dot3(nrm, ap) / n_len;
  cross3(e0, nrm, m);
  const F4 s0 = max(dot3(m, ap), zero) / (sqrt(dot3(e0, e0)) * n_len);
  cross3(e1, nrm, m);
  const F4 s1 = max(dot3(m, bp), zero) / (sqrt(dot3(e1, e1)) * n_len);
  cross3(nrm, e2, m);
  const F4 s2 = max(dot3(m, cp), zero) / (sqrt(dot3(e2, e2)) * n_len);
  const F4 out = max(max(s0, s1), s2);
  const F4 bound2 = h * h + out * out;  // = lower bound^2
  const F4 reach = abs(ap[0]) + abs(ap[1]) + abs(ap[2]) + abs(bp[0]) + abs(bp[1]) + abs(bp[2]) +
                   abs(cp[0]) + abs(cp[1]) + abs(cp[2]);
  const F4 margin = F4::load(leaf.margin) * reach;
  const F4 radius = F4::splat(s.leaf_limit) + margin;
  // Lanes whose bound exceeds the radius are out; NaN or infinite radii keep the lane.
  int keep = ~greater_mask(bound2, radius * radius * F4::splat(1.0f + 1e-5f)) & 0xf;
  if (keep == 0) return;
  // The survivors, nearest bound first; each is checked again against the radius as the
  // exact tests before it shrink it.
  float bound[4], lane_margin[4];
  simd::store(bound, bound2);
  simd::store(lane_margin, margin);
  int lanes[4], count = 0;
  while (keep != 0) {
    const int lane = __builtin_ctz(static_cast<unsigned>(keep));
    keep &= keep - 1;
    const std::uint32_t f = leaf.face[lane];
    if (f == kNoFace || f == s.skip_face) continue;
    int j = count++;
    for (; j > 0 && bound[lanes[j - 1]] > bound[lane]; --j) lanes[j] = lanes[j - 1];
    lanes[j] = lane;
  }
  for (int k = 0; k < count; ++k) {
    const int lane = lanes[k];
    const float r = s.leaf_limit + lane_margin[lane];
    if (k > 0 && bound[lane] > r * r * (1.0f + 1e-5f)) continue;
    consider(s, leaf.face[lane]);
  }
}

double TriangleBvh::find(const Vec3& p, const QueryHint& hint,
                         std::vector<SurfaceHit>& ties) const {
  ties.clear();
  Search s(p, hint, ties);
  s.floor_dist = floor_of(hint);
  // The query in the float frame, and how far rounding may have moved it (plus the corners').
  float qf[3];
  s.cull = to_frame(p, qf, s.slack);
  for (int k = 0; k < 3; ++k) s.pf[k] = F4::splat(qf[k]);

  if (hint.start_face != kNoFace && hint.start_face < eval_.mesh->faces.size()) {
    consider(s, hint.start_face);
    s.skip_face = hint.start_face;
  }

  struct Entry {
    std::uint32_t ref;
    float sq;
  };
  Entry stack[kStackSize];
  int top = 0;
  stack[top++] = {root_, 0.0f};
  while (top > 0) {
    const Entry entry = stack[--top];
    if (entry.sq > s.box_limit2) continue;  // the radius shrank since it was pushed
    if ((entry.ref & kLeafBit) != 0) {
      search_leaf(leaves_[entry.ref & ~kLeafBit], s);
      continue;
    }
    const Node& node = nodes_[entry.ref];
    const F4 d2 = box_sq_distances(node.lo, node.hi, s.pf);
    int keep = ~greater_mask(d2, F4::splat(s.box_limit2)) & 0xf;
    if (keep == 0) continue;
    float dist[4];
    simd::store(dist, d2);
    // Push the kept children farthest first, so the nearest is visited next.
    Entry* kids = stack + top;
    int count = 0;
    while (keep != 0) {
      const int k = __builtin_ctz(static_cast<unsigned>(keep));
      keep &= keep - 1;
      if (node.child[k] == kEmpty) continue;
      const Entry e{node.child[k], dist[k]};
      int j = count++;
      for (; j > 0 && kids[j - 1].sq < e.sq; --j) kids[j] = kids[j - 1];
      kids[j] = e;
    }
    top += count;
    assert(top <= kStackSize);
  }
  // Keep the candidates within the final tie limit, in face order (as the oracle does).
  detail::keep_ties(ties, s.limit);
  return std::sqrt(s.best_sq);
}

// ---------------------------------------------------------------------------------------------
// Batches of coherent queries (packets).

struct TriangleBvh::PacketScratch {
  float qf[kPacketSize][3];
  double slack[kPacketSize];
  // Packets of faces: the supporting planes of the gathered blocks' faces in the float frame
  // (metric/plane_bounds.h: unit normal n and offset d, h = n.p - d the signed distance to the
  // plane, and per edge the outward unit normal m_e within the plane and its offset, out_e =
  // m_e.p - md_e the distance beyond the edge's line), planes[b] for block[b]. Computed in
  // double, stored rounded to float. Faces the bound must not cull have all zeros (bound 0);
  // empty lanes have d = -inf (bound +inf). A query's bounds (4 per selected block) and the
  // indices of those that survive the cutoff.
  // Sparse packets: block[b]'s planes, in the cache; padded to a multiple of 4 with nullptr.
  const BlockPlanes* block_rows[kMaxBlocks + 4];
  BlockPlanes planes[kMaxBlocks];       // ... or here, where two blocks share a cache slot
  std::uint32_t slots[4 * kMaxBlocks];  // dense packets: the candidates (block << 2 | lane)
  std::vector<float> rows;              // ... and their planes as kPlaneRows rows of `stride`
  alignas(32) float bound[4 * kMaxBlocks + kPlaneLanes];
  std::uint32_t survivors[4 * kMaxBlocks];
  std::vector<SurfaceHit> ties, center_ties;
  double center_distance = 0;       // the packet's centre query's answer (packet_bounds)
  std::vector<CachedPlanes> cache;  // 2^kCacheBits slots, allocated with the first packet
  std::uint64_t cache_owner = 0;    // the TriangleBvh::id_ whose planes the cache holds
  float lo[3], hi[3];               // the packet's box (float frame), set while it grows
  // Block packets: the leaf blocks within the packet's reach and their boxes (float frame),
  // rows padded to a multiple of 8 lanes (pad_blocks).
  std::size_t block_count = 0;
  std::uint32_t block[kMaxBlocks + 4];  // + 4: gather_blocks writes a node's four children
  alignas(16) float block_lo[3][kMaxBlocks + 8];
  alignas(16) float block_hi[3][kMaxBlocks + 8];
  std::size_t misses = 0;          // queries of the last packet farther from B than its guess
  bool sparse = false;             // the last packet of faces was sparse (find_packet)
  SurfaceHit firsts[kPacketSize];  // find_packet: each query's exact test of its first face
};

void TriangleBvh::compute_block_planes(std::uint32_t block, BlockPlanes& out) const {
  // From the block's float corners (in cache, unlike the mesh's): the bounds are then those of
  // the float triangles, within corner_error_ of the faces, which every reach includes.
  const Leaf& leaf = leaves_[block];
  kernels_->block_planes(leaf.corner, out);
  for (int lane = 0; lane < 4; ++lane)  // all zeros so far: d = -inf gives a bound of +inf
    if (leaf.face[lane] == kNoFace) out.row[kD][lane] = -kInf;
}

const TriangleBvh::CachedPlanes& TriangleBvh::block_planes(std::uint32_t block,
                                                           PacketScratch& scratch) const {
  if (scratch.cache.empty()) scratch.cache.resize(std::size_t{1} << kCacheBits);
  CachedPlanes& c = scratch.cache[(block * 0x9E3779B1u) >> (32 - kCacheBits)];
  if (c.block != block) {
    compute_block_planes(block, c.planes);
    c.block = block;
  }
  return c;
}

std::size_t TriangleBvh::find_batch(const Vec3* points, const QueryHint* hints, std::size_t count,
                                    BatchHits& out) const {
  out.distance.resize(count);
  out.first.resize(count + 1);
  out.hits.clear();
  out.first[0] = 0;
  out.packet_queries = 0;
  out.block_packet_queries = 0;
  out.sparse_packet_queries = 0;
  out.guess_misses = 0;
  // One scratch per thread, kept across batches: consecutive batches of a thread share faces
  // (the plane cache), and the buffers are not allocated again. A cache filled for another
  // index (or an earlier one at the same address: ids are never reused) is emptied.
  static thread_local PacketScratch scratch;
  if (scratch.cache_owner != id_) {
    scratch.cache.clear();
    scratch.cache_owner = id_;
  }
  std::uint32_t previous = kNoFace;
  // The largest distance of the last query or packet answered, faded in with the earlier ones
  // (kGuessDecay; -1: none).
  double recent = -1.0;
  bool guess_ok = true;  // false: the last packet's guess failed for too many of its queries
  auto single = [&](std::size_t i) {
    QueryHint hint = hints != nullptr ? hints[i] : QueryHint{};
    if (hint.start_face == kNoFace) hint.start_face = previous;
    const double d = find(points[i], hint, scratch.ties);
    append_answer(out, i, d, scratch.ties);
    previous = scratch.ties.front().face;
    recent = d;
  };
  // Packets of faces name them by leaf slot, block << 2 | lane, in 32 bits (short of a billion
  // faces).
  const bool slots_fit = leaves_.size() <= (kNoFace >> 2);
  const detail::PacketExtent extent{packet_extent_ * packet_extent_,
                                    full_packet_extent_ * full_packet_extent_, kFullPacket};
  std::size_t i = 0;
  while (i < count && out.hits.size() < BatchHits::kMaxHits) {
    // Grow a packet of consecutive queries while its box stays within kPacketExtent mean edges
    // (kFullPacketExtent once it holds kFullPacket queries). At least kMinPacket make a packet of
    // faces; fewer, where queries are sparse on B, a block packet.
    // (detail::frame_packet: the queries' float frame and the box, without a branch on the data.)
    const std::size_t j =
        i + (cull_scale_ ? detail::frame_packet(points + i, std::min(count - i, kPacketSize),
                                                frame_, corner_error_, extent, scratch.qf,
                                                scratch.slack, scratch.lo, scratch.hi)
                         : 0);
    if (j == i) {  // beyond the float range: on its own
      single(i++);
      continue;
    }
    // A packet guesses its queries' distances from the last answers (kGuessFactor times the
    // largest) where that is less than half its box's diagonal, the reach its centre's answer
    // would add, unless the guess failed for too many queries of the last packet.
    double guess = recent >= 0.0 && guess_ok ? eval_.limit(kGuessFactor * recent) : -1.0;
    double diag2 = 0.0;
    for (int a = 0; a < 3; ++a)
      diag2 += (static_cast<double>(scratch.hi[a]) - scratch.lo[a]) *
               (static_cast<double>(scratch.hi[a]) - scratch.lo[a]);
    if (guess * frame_.scale > 0.5 * std::sqrt(diag2)) guess = -1.0;
    std::size_t answered = 0;
    if (j - i >= kMinPacket && slots_fit) {
      answered = find_packet(points, hints, i, j - i, previous, guess, scratch, out);
      if (scratch.sparse) out.sparse_packet_queries += answered;
    } else if (j - i >= kMinBlockPacket) {
      answered = find_block_packet(points, hints, i, j - i, previous, guess, scratch, out);
      out.block_packet_queries += answered;
    }
    if (guess >= 0.0 && answered > 0) {
      guess_ok = kGuessMisses * scratch.misses <= answered;
      out.guess_misses += scratch.misses;
    } else if (answered > 0) {
      guess_ok = true;
    }
    if (answered > 0) {
      previous = out.hits[out.first[i + answered - 1]].face;
      const double largest =
          *std::max_element(out.distance.begin() + static_cast<std::ptrdiff_t>(i),
                            out.distance.begin() + static_cast<std::ptrdiff_t>(i + answered));
      recent = recent >= 0.0 ? std::max(largest, kGuessDecay * recent) : largest;
      out.packet_queries += answered;
      i += answered;
    } else {
      single(i++);
      while (i < j && out.hits.size() < BatchHits::kMaxHits) single(i++);
    }
  }
  out.distance.resize(i);
  out.first.resize(i + 1);
  return i;
}

// Breadth first from the root, opening every node whose box lies within reach of [lo, hi]
// (detail::gather_leaf_blocks, or its AVX twin where the CPU runs AVX2, metric/leaf_gather.h).
bool TriangleBvh::gather_blocks(const float lo[3], const float hi[3], double reach,
                                PacketScratch& scratch) const {
  scratch.block_count = 0;
  if ((root_ & kLeafBit) != 0) {  // a single block: its box is the mesh's (within the frame)
    scratch.block[0] = root_ & ~kLeafBit;
    for (int a = 0; a < 3; ++a) {
      scratch.block_lo[a][0] = -kInf;
      scratch.block_hi[a][0] = kInf;
    }
    scratch.block_count = 1;
    return true;
  }
  const float limit2 = round_up_to_float(reach * reach * (1.0 + 1e-5));
  // The nodes opened: beyond kGatherNodes the packet would hold more blocks than it may (a node
  // is opened only where its box lies within reach). Counted with a throwaway counter in the
  // walk, `peer_compare A B 1000000 --threads 2 --repeats 1 --engines meshdev` on nine pairs: the
  // queue ran over in 19 of 67,997 walks of buildings_s40k -> buildings and in none elsewhere,
  // and with a queue twice as long those 19 walks ran over kMaxBlocks instead (389 walks against
  // 370), so the limit only ends them sooner (docs/performance-log.md §3).
  constexpr std::size_t kGatherNodes = 4 * kMaxBlocks;
  std::uint32_t queue[kGatherNodes + 4];  // + 4: a node writes four refs from the tail
  const detail::GatheredBlocks blocks{
      scratch.block,
      {scratch.block_lo[0], scratch.block_lo[1], scratch.block_lo[2]},
      {scratch.block_hi[0], scratch.block_hi[1], scratch.block_hi[2]}};
#if defined(MESHDEV_X86_KERNELS)
  const std::size_t count =
      avx_gather_ ? detail::gather_leaf_blocks_avx2(nodes_.data(), root_, lo, hi, limit2,
                                                    kMaxBlocks, queue, kGatherNodes, blocks)
                  : detail::gather_leaf_blocks(nodes_.data(), root_, lo, hi, limit2, kMaxBlocks,
                                               queue, kGatherNodes, blocks);
#else
  const std::size_t count = detail::gather_leaf_blocks(nodes_.data(), root_, lo, hi, limit2,
                                                       kMaxBlocks, queue, kGatherNodes, blocks);
#endif
  if (count > kMaxBlocks) return false;
  scratch.block_count = count;
  return true;
}

std::size_t TriangleBvh::pad_blocks(PacketScratch& scratch) {
  const std::size_t padded8 = (scratch.block_count + 7) / 8 * 8;
  for (int k = 0; k < 3; ++k)  // padding lanes: never within reach
    for (std::size_t b = scratch.block_count; b < padded8; ++b) {
      scratch.block_lo[k][b] = kInf;
      scratch.block_hi[k][b] = kInf;
    }
  return (scratch.block_count + 3) / 4 * 4;
}

double TriangleBvh::packet_bounds(const Vec3* points, const QueryHint* hints, std::size_t base,
                                  std::size_t n, std::uint32_t start_face, PacketScratch& scratch,
                                  double* limit, double* reach) const {
  assert(n >= 2 && n <= kPacketSize);
  const QueryHint no_hint;
  auto hint_of = [&](std::size_t k) -> const QueryHint& {
    return hints != nullptr ? hints[base + k] : no_hint;
  };
  // The centre query, in full. Its distance bounds every other query's by the triangle
  // inequality: d(p) <= d(c) + |p - c| (d: geometric distances).
  const std::size_t c = n / 2;
  QueryHint center_hint = hint_of(c);
  if (center_hint.start_face == kNoFace) center_hint.start_face = start_face;
  scratch.center_distance = find(points[base + c], center_hint, scratch.center_ties);
  // The centre's distance may be 0 by the identical-triangle rule while it lies up to that
  // check's reach from B (FaceEvaluator::evaluate): its geometric distance is at most its answer
  // plus that reach, and only geometric distances obey the triangle inequality.
  const double center_geometric = scratch.center_distance + floor_of(hint_of(c));
  // Each query's tie limit of that upper bound (1e-9 more for the rounding of computed
  // distances) and its reach in the float frame. Limits here are distances, not squared (no
  // square root of a square on the way).
  double packet_reach = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double separation = norm(points[base + k] - points[base + c]);
    limit[k] = eval_.limit((center_geometric + separation) * (1.0 + 1e-9));
    reach[k] = frame_reach(limit[k], floor_of(hint_of(k)), scratch.slack[k]);
    packet_reach = std::max(packet_reach, reach[k]);
  }
  return packet_reach;
}

double TriangleBvh::guess_bounds(const QueryHint* hints, std::size_t base, std::size_t n,
                                 double guess, const PacketScratch& scratch, double* limit,
                                 double* reach) const {
  const QueryHint no_hint;
  double packet_reach = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    limit[k] = guess;
    reach[k] = frame_reach(guess, floor_of(hints != nullptr ? hints[base + k] : no_hint),
                           scratch.slack[k]);
    packet_reach = std::max(packet_reach, reach[k]);
  }
  return packet_reach;
}

std::size_t TriangleBvh::find_packet(const Vec3* points, const QueryHint* hints, std::size_t base,
                                     std::size_t n, std::uint32_t start_face, double guess,
                                     PacketScratch& scratch, BatchHits& out) const {
  const QueryHint no_hint;
  auto hint_of = [&](std::size_t k) -> const QueryHint& {
    return hints != nullptr ? hints[base + k] : no_hint;
  };
  // With a guess, no centre query: the candidates are the faces within reach of the guessed
  // distance, and each answer is checked as in find_block_packet.
  const bool guessed = guess >= 0.0;
  scratch.misses = 0;
  scratch.sparse = false;
  const std::size_t c = guessed ? n : n / 2;  // the centre answered in full (n: none)
  double initial_limit[kPacketSize], initial_reach[kPacketSize];
  const double packet_reach =
      guessed ? guess_bounds(hints, base, n, guess, scratch, initial_limit, initial_reach)
              : packet_bounds(points, hints, base, n, start_face, scratch, initial_limit,
                              initial_reach);
  auto reach = [&](std::size_t k, double limit) {
    return frame_reach(limit, floor_of(hint_of(k)), scratch.slack[k]);
  };
  if (!std::isfinite(packet_reach) ||
      !gather_blocks(scratch.lo, scratch.hi, packet_reach, scratch) || scratch.block_count == 0)
    return 0;
  const std::size_t blocks = scratch.block_count;
  const std::size_t padded = pad_blocks(scratch);
  const TriMesh& mesh = *eval_.mesh;
  for (std::size_t b = 0; b < blocks; ++b) {
    const char* leaf = reinterpret_cast<const char*>(&leaves_[scratch.block[b]]);
    __builtin_prefetch(leaf);
    __builtin_prefetch(leaf + 64);
    __builtin_prefetch(leaf + 128);
  }
  // Sparse packets: the blocks query k bounds, as indices into the packet's blocks (which[k],
  // selected[k] of them; + 8: the selection writes four or eight entries per group of blocks,
  // past the last it keeps). From the blocks' boxes, which the tree walk wrote.
  static_assert(kMaxBlocks <= 255, "a query's blocks and their indices fit in a byte");
  std::uint8_t which[kPacketSize][kMaxBlocks + 8];
  std::uint8_t selected[kPacketSize];
  const float* const block_lo[3] = {scratch.block_lo[0], scratch.block_lo[1], scratch.block_lo[2]};
  const float* const block_hi[3] = {scratch.block_hi[0], scratch.block_hi[1], scratch.block_hi[2]};
  auto select_blocks = [&](std::size_t k) {
    const float limit2 = round_up_to_float(initial_reach[k] * initial_reach[k] * (1.0 + 1e-5));
#if defined(MESHDEV_X86_KERNELS)
    if (avx_gather_)
      return detail::blocks_near_point_avx2(block_lo, block_hi, blocks, scratch.qf[k], limit2,
                                            which[k]);
#endif
    return detail::blocks_near_point(block_lo, block_hi, blocks, scratch.qf[k], limit2, which[k]);
  };

  // Two layouts of the candidates' planes (metric/plane_bounds.h), from the cache (consecutive
  // packets share most of their blocks). Dense packets, at least kDenseQueries queries per
  // block: the faces of those blocks whose float boxes lie within the packet's reach of its box,
  // laid out once as rows of `stride` floats, and every query bounds all of them (`bounds`).
  // Sparse packets: each block's planes as they are (a copy: two blocks of a packet may share a
  // cache slot), and each query bounds the faces of only the blocks within its own reach
  // (`block_bounds`). Either way the bound of candidate idx is bound[idx], and face_at(k, idx) its
  // face.
  const bool dense = n >= kDenseQueries * blocks;
  scratch.sparse = !dense;
  std::size_t candidates = 0, stride = 0;
  float max_offset = 0.0f;
  if (dense) {
    const F4 qlo[3] = {F4::splat(scratch.lo[0]), F4::splat(scratch.lo[1]),
                       F4::splat(scratch.lo[2])};
    const F4 qhi[3] = {F4::splat(scratch.hi[0]), F4::splat(scratch.hi[1]),
                       F4::splat(scratch.hi[2])};
    const F4 limit2 = F4::splat(round_up_to_float(packet_reach * packet_reach * (1.0 + 1e-5)));
    for (std::size_t b = 0; b < blocks; ++b) {
      const Leaf& leaf = leaves_[scratch.block[b]];
      F4 tlo[3], thi[3];
      for (int k = 0; k < 3; ++k) {
        const F4 x = F4::load(leaf.corner[0][k]), y = F4::load(leaf.corner[1][k]),
                 z = F4::load(leaf.corner[2][k]);
        tlo[k] = min(min(x, y), z);
        thi[k] = max(max(x, y), z);
      }
      int keep = ~greater_mask(box_gap2(tlo, thi, qlo, qhi), limit2) & 0xf;
      while (keep != 0) {
        const int lane = __builtin_ctz(static_cast<unsigned>(keep));
        keep &= keep - 1;
        if (leaf.face[lane] == kNoFace) continue;
        __builtin_prefetch(&mesh.faces[leaf.face[lane]]);
        scratch.slots[candidates++] = scratch.block[b] << 2 | static_cast<std::uint32_t>(lane);
      }
    }
    if (candidates == 0) return 0;
    stride = (candidates + kPlaneLanes - 1) / kPlaneLanes * kPlaneLanes;
    scratch.rows.resize(kPlaneRows * stride);
    float* rows = scratch.rows.data();
    for (std::size_t idx = 0; idx < candidates;) {
      const std::uint32_t slot = scratch.slots[idx];
      const BlockPlanes& f = block_planes(slot >> 2, scratch).planes;
      // A whole block in lane order: four lanes per row at once.
      if ((slot & 3) == 0 && idx + 4 <= candidates && scratch.slots[idx + 3] == slot + 3) {
        for (int r = 0; r < kPlaneRows; ++r)
          std::memcpy(rows + r * stride + idx, f.row[r], sizeof f.row[r]);
        for (int lane = 0; lane < 4; ++lane) max_offset = std::max(max_offset, f.max_offset[lane]);
        idx += 4;
        continue;
      }
      const std::uint32_t lane = slot & 3;
      for (int r = 0; r < kPlaneRows; ++r) rows[r * stride + idx] = f.row[r][lane];
      max_offset = std::max(max_offset, f.max_offset[lane]);
      ++idx;
    }
    for (int r = 0; r < kPlaneRows; ++r)  // padding lanes: bound +inf
      std::fill(rows + r * stride + candidates, rows + (r + 1) * stride, r == kD ? -kInf : 0.0f);
  } else {
    // Every query's selection first, then the planes: the selection reads only the blocks'
    // boxes, so the blocks' lines prefetched above arrive while it runs, where the planes of the
    // blocks met for the first time (about 5.6 of a packet's 17 on torus100k -> 1m) waited for
    // them; and the third pass below reuses it instead of selecting again. `peer_compare A B
    // 1000000 --ab 12`, 1 / 2 threads: torus100k -> 1m 1.037 / 1.040 (1.029 / 1.028 with the
    // third pass still selecting again), torus100k -> torus1m_shuffled 1.035 / 1.031 (--ab 8),
    // the other six pairs 0.986-1.013 (docs/performance-log.md §3, forty-ninth session).
    for (std::size_t k = 0; k < n; ++k)
      if (k != c) selected[k] = static_cast<std::uint8_t>(select_blocks(k));
    const CachedPlanes* cached[kMaxBlocks];
    for (std::size_t b = 0; b < blocks; ++b) {
      const Leaf& leaf = leaves_[scratch.block[b]];
      cached[b] = &block_planes(scratch.block[b], scratch);
      for (int lane = 0; lane < 4; ++lane) {
        if (leaf.face[lane] == kNoFace) continue;
        __builtin_prefetch(&mesh.faces[leaf.face[lane]]);
        max_offset = std::max(max_offset, cached[b]->planes.max_offset[lane]);
      }
    }
    // Where two blocks of the packet share a cache slot, the later one evicted the earlier,
    // whose planes are then computed again outside the cache.
    for (std::size_t b = 0; b < blocks; ++b) {
      scratch.block_rows[b] = &cached[b]->planes;
      if (cached[b]->block == scratch.block[b]) continue;
      compute_block_planes(scratch.block[b], scratch.planes[b]);
      scratch.block_rows[b] = &scratch.planes[b];
    }
    for (std::size_t b = blocks; b < padded; ++b) scratch.block_rows[b] = nullptr;
  }
  // Candidate idx's face for query k (a dense packet's candidates are every query's: any k).
  auto face_at = [&](std::size_t k, std::size_t idx) {
    return dense ? leaves_[scratch.slots[idx] >> 2].face[scratch.slots[idx] & 3]
                 : leaves_[scratch.block[which[k][idx >> 2]]].face[idx & 3];
  };
  // The candidates' faces in the mesh (above) and their corners' positions (the exact tests read
  // them, in double), prefetched: otherwise a face's first exact test in the packet waited for
  // its misses one at a time, which the evaluation's long body keeps from overlapping. Where the
  // target's faces are stored in no spatial order (torus1m's shuffled) the exact tests took
  // 20 % of the process; peer_compare torus100k -> that mesh +26 %, -> torus1m itself +2.5 %,
  // the others within noise (docs/performance-log.md §3). Dense packets: every candidate's, now.
  // Sparse packets: only each query's first face, as the first pass below finds it (the tests of
  // the second pass read those), instead of every gathered block's four: `peer_compare --ab 8`,
  // 1 / 2 threads, torus100k -> 1m 1.009 / 1.011 and 1.019 / 1.009, -> torus1m_shuffled 1.011 /
  // 1.003, the other pairs within noise (docs/performance-log.md §3).
  auto prefetch_corners = [&](std::uint32_t face) {
    const Triangle& t = mesh.faces[face];
    for (int corner = 0; corner < 3; ++corner) __builtin_prefetch(&mesh.positions[t[corner]]);
  };
  if (dense)
    for (std::size_t idx = 0; idx < candidates; ++idx) prefetch_corners(face_at(0, idx));

  // Query k's bounds into scratch.bound (count: the selected blocks' lanes), the smallest and the
  // runner-up (NaN bounds become 0: evaluated first, never culled).
  auto bounds_of = [&](std::size_t k, std::size_t count) {
    return dense ? kernels_->bounds(scratch.rows.data(), stride, candidates, scratch.qf[k],
                                    scratch.bound)
                 : kernels_->block_bounds(scratch.block_rows, which[k], count / 4, scratch.qf[k],
                                          scratch.bound);
  };

  // Each query: float lower bounds sqrt(h^2 + max(out_e, 0)^2) of its candidates, then the
  // survivors evaluated exactly, smallest bound first, until the bound passes the tie limit.
  // The bound's rounding is at most about 6 u (|p|_1 + max offset) (coefficients rounded to
  // float, three products and sums; fewer roundings where the kernel fuses multiply-adds) plus
  // 1e-9 (|p|_1 + 2) from the double computation of normals of faces with kappa <= kMaxKappa:
  // the margin 16 u (|p|_1 + max offset + 2) covers both with room.
  // In three passes over the packet's queries. First each query's bounds (sparse packets: of the
  // blocks it selects) give its candidate of smallest bound and the runner-up; then those first
  // candidates are tested exactly, four queries at a time (FaceEvaluator::evaluate_x4: AVX2 lanes
  // where the closest point lies in the face's interior, as it mostly does); then each query
  // ends as before. Its bounds are computed again, the same, for the few queries whose runner-up
  // lies within the cutoff (sparse packets: over its selection, kept). Against the exact test
  // query by query (chunk-interleaved, 1 and 2 threads: torus100k -> 1m +6-10 %, torus1m -> 100k
  // +17 %, torus100k -> 10k +10-16 %, armadillo +11 %, buildings +3-8 %; docs/performance-log.md
  // §3).
  enum : std::uint8_t { kCentre, kInFull, kTested };
  std::uint8_t status[kPacketSize];
  std::uint32_t first_face[kPacketSize], first_idx[kPacketSize], counted[kPacketSize];
  float runner_up[kPacketSize];
  std::uint32_t tested[kPacketSize];
  std::size_t n_tested = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (k == c) {
      status[k] = kCentre;
      continue;
    }
    std::size_t count = candidates;
    if (!dense) {
      if (selected[k] == 0) {  // none within the guessed reach
        status[k] = kInFull;
        continue;
      }
      count = 4 * std::size_t{selected[k]};
    }
    const LeastBounds least = bounds_of(k, count);
    first_face[k] = face_at(k, least.first);
    if (first_face[k] == kNoFace) {  // every bound +inf (only empty lanes)
      status[k] = kInFull;
      continue;
    }
    status[k] = kTested;
    if (!dense) prefetch_corners(first_face[k]);  // for the first exact tests, below
    first_idx[k] = static_cast<std::uint32_t>(least.first);
    counted[k] = static_cast<std::uint32_t>(count);
    runner_up[k] = least.runner_up;
    tested[n_tested++] = static_cast<std::uint32_t>(k);
  }
  // The faces of smallest bound, exactly, four queries at a time: each gives its query's tie
  // limit, usually final.
  for (std::size_t t = 0; t < n_tested; t += 4) {
    const int lanes = static_cast<int>(std::min<std::size_t>(4, n_tested - t));
    const Vec3* p4[4];
    std::uint32_t f4[4];
    const QueryHint* h4[4];
    SurfaceHit* o4[4];
    for (int l = 0; l < lanes; ++l) {
      const std::size_t k = tested[t + static_cast<std::size_t>(l)];
      p4[l] = &points[base + k];
      f4[l] = first_face[k];
      h4[l] = &hint_of(k);
      o4[l] = &scratch.firsts[k];
    }
    eval_.evaluate_x4(p4, f4, h4, lanes, o4);
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0 && out.hits.size() >= BatchHits::kMaxHits) return k;  // answered k of n
    const QueryHint& hint = hint_of(k);
    if (status[k] == kCentre) {
      append_answer(out, base + k, scratch.center_distance, scratch.center_ties);
      continue;
    }
    if (status[k] == kInFull) {
      answer_in_full(points, base, k, hint, kNoFace, start_face, scratch, out);
      continue;
    }
    const float* qf = scratch.qf[k];
    const Vec3& p = points[base + k];
    std::vector<SurfaceHit>& ties = scratch.ties;
    const double margin =
        16.0 * kUnit * (std::fabs(qf[0]) + std::fabs(qf[1]) + std::fabs(qf[2]) + max_offset + 2.0);
    auto cutoff_of = [&](double r) {  // r: a reach
      return round_up_to_float((r + margin) * (r + margin) * (1.0 + 1e-5));
    };
    // The first face's answer gives the tie limit, usually final.
    const SurfaceHit& first = scratch.firsts[k];
    double best_sq = first.sq_distance, best = std::sqrt(best_sq);
    double limit = eval_.limit(best), limit_sq = limit * limit;  // = eval_.limit_sq(best_sq)
    float cutoff = cutoff_of(std::min(initial_reach[k], reach(k, limit)));
    // Most queries have no candidate but the first within the cutoff, which the runner-up tells
    // without the scan for survivors and its branches on the bounds (chunk-interleaved, 1 and 2
    // threads: torus100k -> 1m +1.6-1.8 %, torus1m -> 100k +2.0-2.4 %, torus100k -> 10k
    // +1.5-2.2 %, armadillo +0.9-1.3 %, buildings -0.6 to +0.1 %; docs/performance-log.md §3).
    std::size_t left = 0;
    if (!(runner_up[k] > cutoff)) {
      bounds_of(k, counted[k]);
      left =
          kernels_->survivors(scratch.bound, counted[k], cutoff, first_idx[k], scratch.survivors);
    }
    if (left == 0) {
      // The first face alone, as most queries end: its answer goes straight into the batch, as
      // keep_ties and append_answer would leave it, without the tie list, keep_ties' call and the
      // insertion's copy (chunk-interleaved, 1 / 2 threads: torus100k -> 1m +2.0 / +2.0 %, the
      // other pairs +1.5 to +3.6 %; docs/performance-log.md §3).
      if (guessed && !(limit_sq <= guess * guess)) {  // farther than guessed: the whole tree
        answer_in_full(points, base, k, hint, first.face, start_face, scratch, out);
        continue;
      }
      out.distance[base + k] = best;
      if (!(first.sq_distance > limit_sq)) out.hits.push_back(first);
      out.first[base + k + 1] = static_cast<std::uint32_t>(out.hits.size());
      continue;
    }
    ties.clear();
    ties.push_back(first);
    while (left > 0) {
      std::size_t pick = 0;
      for (std::size_t s = 1; s < left; ++s)
        if (scratch.bound[scratch.survivors[s]] < scratch.bound[scratch.survivors[pick]]) pick = s;
      const std::uint32_t idx = scratch.survivors[pick];
      if (scratch.bound[idx] > cutoff) break;
      scratch.survivors[pick] = scratch.survivors[--left];
      const std::uint32_t face = face_at(k, idx);
      if (face == kNoFace) continue;  // an empty lane (bound +inf) under a cutoff of +inf
      const SurfaceHit h = eval_.evaluate(p, face, hint);
      if (h.sq_distance > limit_sq) continue;
      if (h.sq_distance < best_sq) {
        best_sq = h.sq_distance;
        best = std::sqrt(best_sq);
        limit = eval_.limit(best);
        limit_sq = limit * limit;
        cutoff = std::min(cutoff, cutoff_of(reach(k, limit)));
      }
      ties.push_back(h);
    }
    if (guessed && !(limit_sq <= guess * guess)) {  // farther than guessed: the whole tree
      answer_in_full(points, base, k, hint, first.face, start_face, scratch, out);
      continue;
    }
    detail::keep_ties(ties, limit_sq);
    append_answer(out, base + k, best, ties);
  }
  return n;
}

void TriangleBvh::answer_in_full(const Vec3* points, std::size_t base, std::size_t k,
                                 const QueryHint& hint, std::uint32_t from,
                                 std::uint32_t start_face, PacketScratch& scratch,
                                 BatchHits& out) const {
  QueryHint full = hint;
  if (from != kNoFace) full.start_face = from;
  if (full.start_face == kNoFace)
    full.start_face = k > 0 ? out.hits[out.first[base + k - 1]].face : start_face;
  append_answer(out, base + k, find(points[base + k], full, scratch.ties), scratch.ties);
  ++scratch.misses;
}

std::size_t TriangleBvh::find_block_packet(const Vec3* points, const QueryHint* hints,
                                           std::size_t base, std::size_t n,
                                           std::uint32_t start_face, double guess,
                                           PacketScratch& scratch, BatchHits& out) const {
  const QueryHint no_hint;
  auto hint_of = [&](std::size_t k) -> const QueryHint& {
    return hints != nullptr ? hints[base + k] : no_hint;
  };
  // With a guess, the blocks within reach of the guessed distance are gathered and every query is
  // searched in them, each checked afterwards (below); without one, the centre query is answered
  // in full first and bounds the others.
  const bool guessed = guess >= 0.0;
  scratch.misses = 0;
  const std::size_t c = guessed ? n : n / 2;  // the centre answered in full (n: none)
  double initial_limit[kPacketSize], initial_reach[kPacketSize];
  const double packet_reach =
      guessed ? guess_bounds(hints, base, n, guess, scratch, initial_limit, initial_reach)
              : packet_bounds(points, hints, base, n, start_face, scratch, initial_limit,
                              initial_reach);
  if (!std::isfinite(packet_reach) ||
      !gather_blocks(scratch.lo, scratch.hi, packet_reach, scratch) || scratch.block_count == 0)
    return 0;
  const std::size_t blocks = scratch.block_count;
  const std::size_t padded = pad_blocks(scratch);

  // Each query: the distances to the blocks' boxes, then the blocks within its reach, nearest
  // first, as in find(), with the radii started from the centre's bound instead of a start face.
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0 && out.hits.size() >= BatchHits::kMaxHits) return k;  // answered k of n
    if (k == c) {
      append_answer(out, base + k, scratch.center_distance, scratch.center_ties);
      continue;
    }
    const QueryHint& hint = hint_of(k);
    std::vector<SurfaceHit>& ties = scratch.ties;
    ties.clear();
    Search s(points[base + k], hint, ties);
    s.floor_dist = floor_of(hint);
    s.cull = true;  // packets hold only queries to_frame can cull
    s.slack = scratch.slack[k];
    for (int a = 0; a < 3; ++a) s.pf[a] = F4::splat(scratch.qf[k][a]);
    narrow(s, initial_limit[k]);
    if (guessed && k > 0) {  // the query before bounds this one (as the centre does, above)
      const double before = out.distance[base + k - 1] + floor_of(hint_of(k - 1));
      const double separation = norm(points[base + k] - points[base + k - 1]);
      narrow(s, eval_.limit((before + separation) * (1.0 + 1e-9)));
    }

    // The blocks' squared box distances; searched blocks become +inf. The nearest is searched
    // first (its exact distance makes the radius tight), then the nearest of the rest while it
    // is within the radius.
    alignas(16) float dist[kMaxBlocks + 4];
    for (std::size_t b = 0; b < padded; b += 4) {
      F4 blo[3], bhi[3];
      for (int a = 0; a < 3; ++a) {
        blo[a] = F4::load(scratch.block_lo[a] + b);
        bhi[a] = F4::load(scratch.block_hi[a] + b);
      }
      simd::store(dist + b, box_sq_distances_f4(blo, bhi, s.pf));
    }
    // `remaining`: the blocks not searched yet. A searched block's distance becomes +inf, so a
    // finite least distance is always a remaining block's; where the least is +inf (blocks too
    // far for float, with no finite radius yet) a remaining block is taken from the mask, never
    // a searched one or a padding lane (fuzz_nearest_point found the loop re-searching those).
    constexpr std::size_t kWords = (kMaxBlocks + 63) / 64;
    std::uint64_t remaining[kWords];
    for (std::size_t w = 0; w < kWords; ++w) {
      const std::size_t from = 64 * w;
      remaining[w] = blocks >= from + 64 ? ~std::uint64_t{0}
                     : blocks > from     ? (std::uint64_t{1} << (blocks - from)) - 1
                                         : 0;
    }
    std::size_t left = blocks;  // the bits set in `remaining`
    while (left != 0) {
      F4 lowest = F4::load(dist);
      for (std::size_t b = 4; b < padded; b += 4) lowest = min(lowest, F4::load(dist + b));
      float lanes[4];
      simd::store(lanes, lowest);
      const float least = std::min(std::min(lanes[0], lanes[1]), std::min(lanes[2], lanes[3]));
      if (!(least <= s.box_limit2)) break;
      std::size_t at = 0;
      if (least == kInf) {
        std::size_t w = 0;
        while (remaining[w] == 0) ++w;
        at = 64 * w + static_cast<std::size_t>(__builtin_ctzll(remaining[w]));
      } else {
        const F4 wanted = F4::splat(least);
        for (;; at += 4) {
          const int hit = equal_mask(F4::load(dist + at), wanted);
          if (hit != 0) {
            at += static_cast<std::size_t>(__builtin_ctz(static_cast<unsigned>(hit)));
            break;
          }
        }
      }
      assert(at < blocks && (remaining[at / 64] >> (at % 64) & 1) != 0);
      remaining[at / 64] &= ~(std::uint64_t{1} << (at % 64));
      --left;
      dist[at] = kInf;
      search_leaf(leaves_[scratch.block[at]], s);
    }
    // A guess is checked: every face within the tie limit found lies within reach of the
    // gathered blocks only if that limit is within the guess. Otherwise (the query is farther
    // from B than guessed) the whole tree is searched, from the best face found.
    if (guessed && !(s.limit <= guess * guess)) {
      QueryHint full = hint;
      if (!ties.empty()) full.start_face = ties.front().face;
      if (full.start_face == kNoFace)
        full.start_face = k > 0 ? out.hits[out.first[base + k - 1]].face : start_face;
      append_answer(out, base + k, find(points[base + k], full, ties), ties);
      ++scratch.misses;
      continue;
    }
    detail::keep_ties(ties, s.limit);
    append_answer(out, base + k, std::sqrt(s.best_sq), ties);
  }
  return n;
}

}  // namespace meshdev
