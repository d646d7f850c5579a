#pragma once
// Nearest point on a triangle mesh's surface, with ALL equidistant candidates (the paper's tie
// rule needs them). Two implementations answer the same queries with the same numbers: the BVH
// (triangle_bvh.h) and the brute-force oracle (nearest_point_brute.h).
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "metric/closest_point_triangle.h"
#include "metric/mesh.h"

namespace meshdev {

// One candidate nearest point: a face of the target, the closest point on it and where it lies.
// 64 bytes: the feature sits beside the face, in what was the face's padding (72 bytes with it
// after the barycentrics: BatchHits and the nearest points kept per sample take 11 % less).
struct SurfaceHit {
  std::uint32_t face = kNoFace;
  Feature feature = Feature::kVertex;
  double sq_distance = 0;               // absolute units^2
  std::array<double, 3> bary{1, 0, 0};  // on the target face's corners 0, 1, 2
  Vec3 point;
};
static_assert(sizeof(SurfaceHit) == 64, "SurfaceHit: one cache line's size");

// When two candidates count as equally near (docs/metric.md "Ties"): a face is a tie when its
// distance d satisfies d <= d_min (1 + relative) + absolute, absolute = absolute_fraction x the
// target's bounding-box diagonal. Rounding makes exactly-equal distances rare, so a tolerance is
// needed; 1e-9 relative is far above double rounding (1e-16) and far below any real difference.
// Both must be finite and >= 0 (the indexes throw InvalidInput otherwise); a relative tolerance
// below kMinTieRelative, 0 included, is raised to it.
struct TieOptions {
  double relative = 1e-9;            // relative to the minimum distance
  double absolute_fraction = 1e-12;  // of the target's bbox diagonal (covers d_min = 0)
};

// The least relative tie tolerance honoured. Below about 2.5 double rounding units the squared
// tie limit of the minimum d, (d (1 + relative))^2 with each step rounded, can fall below the
// rounded d^2 itself, and the nearest face would drop out of its own tie set (leaving a query
// with no answer). From 1e-15 on it cannot: (d (1 + 1e-15))^2 exceeds d^2 by about 2e-15 of it,
// more than the five roundings on the way can take (5.6e-16).
constexpr double kMinTieRelative = 1e-15;

// What a query may know beyond its position.
struct QueryHint {
  // The corners of the reference-mesh triangle the query was sampled on, and its barycentric
  // coordinates there. If the target has a triangle with bitwise-identical corners (in any
  // order), the query lies on it exactly: distance 0, barycentrics carried over. This removes the
  // 1e-16 rounding of re-projecting a sample onto its own triangle, so identical meshes compare
  // to exactly 0 (reliability.md §6.3).
  const Vec3* source = nullptr;  // 3 corners, or nullptr
  // ... or that triangle by index: face `source_face` of `source_mesh` (used when `source` is
  // null). Its corners are read only where a target triangle comes that close, not for every
  // query (compute_deviations: +1-2 % on torus1m -> 100k, docs/performance-log.md §3).
  const TriMesh* source_mesh = nullptr;
  std::uint32_t source_face = kNoFace;
  std::array<double, 3> source_bary{1, 0, 0};
  // A target face tested first (e.g. the previous sample's nearest). Only gives an early upper
  // bound: results do not depend on it.
  std::uint32_t start_face = kNoFace;

  bool has_source() const { return source != nullptr || source_mesh != nullptr; }
  // The source triangle's corners: `source`, or the mesh's corners of source_face copied to
  // `out`. Precondition: has_source().
  const Vec3* source_corners(Vec3 out[3]) const {
    if (source != nullptr) return source;
    for (int c = 0; c < 3; ++c) out[c] = source_mesh->positions[source_mesh->faces[source_face][c]];
    return out;
  }
};

// The answers to a batch of queries (NearestPointIndex::find_batch), flattened so a batch of
// thousands of queries makes no per-query allocation.
struct BatchHits {
  // find_batch stops after the query that brings the ties held to this many (64 bytes each), so
  // a batch stays a few MB even where every query ties with millions of faces.
  static constexpr std::size_t kMaxHits = std::size_t{1} << 16;

  std::vector<double> distance;      // per query: the minimum distance (absolute)
  std::vector<std::uint32_t> first;  // per query, plus one: ties of query i are
                                     // hits[first[i]] .. hits[first[i + 1] - 1], sorted by face
  std::vector<SurfaceHit> hits;
  std::size_t packet_queries = 0;  // how many were answered in packets (TriangleBvh), for tests
                                   // and benchmarks; the answers do not depend on it
  std::size_t block_packet_queries = 0;   // of those, how many in block packets
  std::size_t sparse_packet_queries = 0;  // ... and how many in sparse packets of faces (each
                                          // query bounds only the blocks within its reach)
  std::size_t guess_misses = 0;  // of the packets' queries, how many were farther from the target
                                 // than their packet guessed (searched again in full)

  std::size_t size() const { return distance.size(); }
  const SurfaceHit* ties_begin(std::size_t i) const { return hits.data() + first[i]; }
  std::size_t tie_count(std::size_t i) const { return first[i + 1] - first[i]; }
};

// A nearest-point index over one target mesh. Thread-safe for concurrent queries.
class NearestPointIndex {
 public:
  virtual ~NearestPointIndex() = default;
  virtual std::string name() const = 0;

  // Fills `ties` with every face within the tie tolerance of the minimum distance from p,
  // sorted by face index (so ties.front() is deterministic), and returns the minimum distance
  // (absolute). Precondition: the target has at least one face (checked at construction).
  virtual double find(const Vec3& p, const QueryHint& hint,
                      std::vector<SurfaceHit>& ties) const = 0;

  // Answers the first n of `count` queries at once and returns n (1 <= n <= count for count > 0;
  // n < count only once BatchHits::kMaxHits ties are held), each exactly as find(points[i],
  // hints[i]) would: same distance, same ties in the same order; `out` holds those n. Queries
  // given in a coherent order (consecutive ones near each other, e.g. samples generated face by
  // face or sorted along a Morton curve) let an index share work between them (TriangleBvh:
  // packets). A hint whose start_face is kNoFace gets the previous query's nearest face. `hints`
  // may be nullptr (no hints). The default loops over find(). O(n) queries.
  virtual std::size_t find_batch(const Vec3* points, const QueryHint* hints, std::size_t count,
                                 BatchHits& out) const;
};

enum class IndexKind {
  kGrid,        // hashed uniform grid with a BVH fallback (triangle_grid.h)
  kBvh,         // bounding-volume hierarchy (triangle_bvh.h)
  kBruteForce,  // every face, the test oracle (nearest_point_brute.h)
};

// Builds the index of the given kind over `target` (kept by reference: it must outlive the
// index) with `threads` OpenMP threads (0 = OpenMP's default; the index is the same for any
// count). Throws InvalidInput if the target has no faces.
std::unique_ptr<NearestPointIndex> make_nearest_point_index(const TriMesh& target, IndexKind kind,
                                                            const TieOptions& ties = {},
                                                            int threads = 0);

namespace detail {

// The shared per-face evaluation and tie arithmetic, so both indexes compute identical numbers.
struct FaceEvaluator {
  const TriMesh* mesh = nullptr;
  BoundingBox box;  // of the mesh's referenced vertices (bounding_box), for the indices' frames
  double tie_relative = 0;
  double tie_absolute = 0;    // absolute units
  double exact_check_sq = 0;  // hits closer than this are checked for an identical triangle

  // A bounding sphere per face (float centre, radius rounded up so it stays conservative): a
  // face whose sphere is farther than the current tie limit cannot be a candidate, so it is
  // skipped without the exact test. 16 bytes per face; empty unless asked for.
  struct Sphere {
    float center[3];
    float radius;
  };
  std::vector<Sphere> spheres;
  bool x4 = false;  // evaluate_x4 may use face_interior_x4 (the CPU runs AVX2)

  // threads: OpenMP threads for the passes over the mesh (0 = OpenMP's default). Throws
  // InvalidInput for tie tolerances that are negative or not finite (TieOptions).
  FaceEvaluator(const TriMesh& m, const TieOptions& ties, bool with_spheres = true,
                int threads = 0);
  // The same from the mesh's boxes, for a caller that has them: `corner_box`, the box of the
  // referenced vertices (corner_bounding_box); `position_box`, the box of all vertices
  // (position_bounding_box). O(F) with spheres, else O(1).
  FaceEvaluator(const TriMesh& m, const TieOptions& ties, const BoundingBox& corner_box,
                const BoundingBox& position_box, bool with_spheres);
  SurfaceHit evaluate(const Vec3& p, std::uint32_t face, const QueryHint& hint) const;
  // evaluate(*p[l], face[l], *hint[l]) for the lanes l < lanes (1 <= lanes <= 4) into *out[l], bit
  // for bit: the face regions four at a time where the CPU runs AVX2 (face_interior_x4), the other
  // lanes one by one. O(lanes).
  void evaluate_x4(const Vec3* const p[4], const std::uint32_t face[4],
                   const QueryHint* const hint[4], int lanes, SurfaceHit* const out[4]) const;
  // Tie limit (not squared) for a minimum distance `best` (not squared).
  double limit(double best) const { return best * (1.0 + tie_relative) + tie_absolute; }
  // Squared tie limit for a minimum squared distance: limit(sqrt(best_sq))^2.
  double limit_sq(double best_sq) const;
  // True if face cannot lie within distance `limit` (not squared) of p. Conservative: never
  // true for a face the exact test would keep.
  bool rejects(const Vec3& p, std::uint32_t face, double limit) const {
    const Sphere& s = spheres[face];
    const double dx = p.x - s.center[0], dy = p.y - s.center[1], dz = p.z - s.center[2];
    const double reach = (static_cast<double>(s.radius) + limit) * (1.0 + 1e-12);
    return dx * dx + dy * dy + dz * dz > reach * reach;
  }
};

// Keeps the candidates within the final squared tie limit, sorted by face index (what the
// brute-force oracle returns). O(k log k) for k candidates.
void keep_ties(std::vector<SurfaceHit>& ties, double limit_sq);

}  // namespace detail
}  // namespace meshdev
