#include "metric/nearest_point.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "metric/errors.h"
#include "metric/face_interior_x4.h"
#include "metric/nearest_point_brute.h"
#include "metric/plane_bounds.h"
#include "metric/triangle_bvh.h"
#include "metric/triangle_grid.h"

namespace meshdev {

std::unique_ptr<NearestPointIndex> make_nearest_point_index(const TriMesh& target, IndexKind kind,
                                                            const TieOptions& ties, int threads) {
  if (target.faces.empty())
    throw InvalidInput("the target mesh has no faces: nearest points on a surface need triangles");
  if (kind == IndexKind::kBruteForce) return std::make_unique<NearestPointBrute>(target, ties);
  if (kind == IndexKind::kBvh) return std::make_unique<TriangleBvh>(target, ties, threads);
  return std::make_unique<TriangleGrid>(target, ties, threads);
}

std::size_t NearestPointIndex::find_batch(const Vec3* points, const QueryHint* hints,
                                          std::size_t count, BatchHits& out) const {
  out.distance.resize(count);
  out.first.resize(count + 1);
  out.hits.clear();
  out.first[0] = 0;
  out.packet_queries = 0;
  out.block_packet_queries = 0;
  out.sparse_packet_queries = 0;
  out.guess_misses = 0;
  std::vector<SurfaceHit> ties;
  std::uint32_t previous = kNoFace;
  std::size_t i = 0;
  for (; i < count && out.hits.size() < BatchHits::kMaxHits; ++i) {
    QueryHint hint = hints != nullptr ? hints[i] : QueryHint{};
    if (hint.start_face == kNoFace) hint.start_face = previous;
    out.distance[i] = find(points[i], hint, ties);
    out.hits.insert(out.hits.end(), ties.begin(), ties.end());
    out.first[i + 1] = static_cast<std::uint32_t>(out.hits.size());
    previous = ties.front().face;
  }
  out.distance.resize(i);
  out.first.resize(i + 1);
  return i;
}

namespace detail {
namespace {

// perm[i] = j such that corner i of the target triangle equals source corner j; false if the
// two triangles do not have the same three corners.
bool match_corners(const Vec3* source, const Vec3& a, const Vec3& b, const Vec3& c, int perm[3]) {
  const Vec3* corners[3] = {&a, &b, &c};
  bool used[3] = {false, false, false};
  for (int i = 0; i < 3; ++i) {
    perm[i] = -1;
    for (int j = 0; j < 3; ++j)
      if (!used[j] && *corners[i] == source[j]) {
        perm[i] = j;
        used[j] = true;
        break;
      }
    if (perm[i] < 0) return false;
  }
  return true;
}

// The tie tolerances as given, or InvalidInput: both finite and >= 0 (a NaN or a negative one
// would leave queries with no tie at all, not even their nearest face).
const TieOptions& checked(const TieOptions& ties) {
  auto fine = [](double x) { return std::isfinite(x) && x >= 0.0; };
  if (!fine(ties.relative) || !fine(ties.absolute_fraction)) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "tie tolerances must be finite and >= 0: relative %g, absolute_fraction %g",
                  ties.relative, ties.absolute_fraction);
    throw InvalidInput(text);
  }
  return ties;
}

}  // namespace

FaceEvaluator::FaceEvaluator(const TriMesh& m, const TieOptions& ties, bool with_spheres,
                             int threads)
    : FaceEvaluator(m, ties, corner_bounding_box(m, threads), position_bounding_box(m, threads),
                    with_spheres) {}

FaceEvaluator::FaceEvaluator(const TriMesh& m, const TieOptions& ties,
                             const BoundingBox& corner_box, const BoundingBox& position_box,
                             bool with_spheres)
    : mesh(&m), box(corner_box), tie_relative(std::max(checked(ties).relative, kMinTieRelative)) {
  const double diag = box.diagonal();
  tie_absolute = ties.absolute_fraction * diag;
  // Sample points far from the origin carry the rounding of their absolute coordinates (about
  // 1e-16 of their magnitude), so the identical-triangle check must look that far. It is only a
  // shortcut: the check itself requires bitwise-identical corners. The magnitude is the largest
  // |coordinate| of any vertex (NaN skipped), read off the box of all vertices.
  double magnitude = 0.0;
  for (int k = 0; k < 3; ++k)
    if (position_box.min[k] <= position_box.max[k])  // an axis whose every coordinate is NaN: none
      magnitude =
          std::max({magnitude, std::fabs(position_box.min[k]), std::fabs(position_box.max[k])});
  const double reach = 1e-9 * diag + 1e-14 * magnitude;
  exact_check_sq = reach * reach;
#if defined(MESHDEV_X86_KERNELS)
  x4 = simd_level() != SimdLevel::kBaseline;
#endif
  if (!with_spheres) return;
  spheres.resize(m.faces.size());
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    const Triangle& t = m.faces[f];
    const Vec3 c = (1.0 / 3.0) * (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]);
    Sphere& s = spheres[f];
    for (int k = 0; k < 3; ++k) s.center[k] = static_cast<float>(c[k]);
    const Vec3 cf{s.center[0], s.center[1], s.center[2]};
    double r = 0.0;
    for (std::uint32_t v : t) r = std::max(r, norm(m.positions[v] - cf));
    // Round up so the float radius still covers every corner.
    float rf = static_cast<float>(r);
    while (static_cast<double>(rf) < r)
      rf = std::nextafter(rf, std::numeric_limits<float>::infinity());
    s.radius = rf;
  }
}

namespace {

// The identical-triangle rule of FaceEvaluator::evaluate for a hit within the check's reach: if
// the query's source triangle has the target triangle's corners (in any order), the hit becomes
// distance 0 with the source's barycentrics. Out of line: it is rarely reached.
[[gnu::noinline]] void apply_identical_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                                const Vec3& c, const QueryHint& hint,
                                                SurfaceHit& s) {
  int perm[3];
  Vec3 corners[3];
  if (!match_corners(hint.source_corners(corners), a, b, c, perm)) return;
  s.sq_distance = 0.0;
  s.point = p;
  for (int i = 0; i < 3; ++i) s.bary[i] = hint.source_bary[perm[i]];
  int zeros = (s.bary[0] == 0.0) + (s.bary[1] == 0.0) + (s.bary[2] == 0.0);
  s.feature = zeros >= 2 ? Feature::kVertex : (zeros == 1 ? Feature::kEdge : Feature::kFace);
}

// FaceEvaluator::evaluate: the corners are read from the mesh in place and the closest point
// inlined, so an exact test makes no call and no copy of the triangle (420 -> 348 instructions in
// the face region, docs/performance-log.md §3).
[[gnu::always_inline]] inline SurfaceHit evaluate_face(const FaceEvaluator& eval, const Vec3& p,
                                                       std::uint32_t face, const Vec3& a,
                                                       const Vec3& b, const Vec3& c,
                                                       const TriangleFrame& frame,
                                                       const QueryHint& hint) {
  const TriangleHit h = closest_point_on_triangle(p, a, b, c, frame);
  SurfaceHit s{face, h.feature, h.sq_distance, h.bary, h.point};
  if (hint.has_source() && s.sq_distance <= eval.exact_check_sq)
    apply_identical_triangle(p, a, b, c, hint, s);
  return s;
}

}  // namespace

SurfaceHit FaceEvaluator::evaluate(const Vec3& p, std::uint32_t face, const QueryHint& hint) const {
  const Triangle& t = mesh->faces[face];
  const Vec3 &a = mesh->positions[t[0]], &b = mesh->positions[t[1]], &c = mesh->positions[t[2]];
  return evaluate_face(*this, p, face, a, b, c, triangle_frame(a, b, c), hint);
}

void FaceEvaluator::evaluate_x4(const Vec3* const p[4], const std::uint32_t face[4],
                                const QueryHint* const hint[4], int lanes,
                                SurfaceHit* const out[4]) const {
  unsigned done = 0;
#if defined(MESHDEV_X86_KERNELS)
  if (x4 && lanes > 1) {
    const Vec3 *q[4], *a[4], *b[4], *c[4];
    SurfaceHit* o[4];
    for (int l = 0; l < 4; ++l) {  // lanes past the last repeat the first
      const int from = l < lanes ? l : 0;
      const Triangle& t = mesh->faces[face[from]];
      q[l] = p[from];
      a[l] = &mesh->positions[t[0]];
      b[l] = &mesh->positions[t[1]];
      c[l] = &mesh->positions[t[2]];
      o[l] = out[from];
    }
    done = face_interior_x4(q, a, b, c, o) & ((1u << lanes) - 1u);
    // Without a branch per lane: the faces written to every lane (those past the last repeat
    // the first), then only the lanes close enough for the identical-triangle rule, and those
    // left to the walk (chunk-interleaved, 1 and 2 threads: +0.3 to +1.1 % on the torus pairs;
    // docs/performance-log.md §3).
    unsigned near = 0;
    for (int l = 0; l < 4; ++l) {
      o[l]->face = face[l < lanes ? l : 0];
      near |= static_cast<unsigned>(o[l]->sq_distance <= exact_check_sq) << l;
    }
    for (near &= done; near != 0; near &= near - 1) {
      const int l = __builtin_ctz(near);
      if (hint[l]->has_source())
        apply_identical_triangle(*p[l], *a[l], *b[l], *c[l], *hint[l], *out[l]);
    }
  }
#endif
  for (unsigned rest = ~done & ((1u << lanes) - 1u); rest != 0; rest &= rest - 1) {
    const int l = __builtin_ctz(rest);
    *out[l] = evaluate(*p[l], face[l], *hint[l]);
  }
}

double FaceEvaluator::limit_sq(double best_sq) const {
  const double l = limit(std::sqrt(best_sq));
  return l * l;
}

void keep_ties(std::vector<SurfaceHit>& ties, double limit_sq) {
  if (ties.size() == 1) {  // the common case
    if (ties[0].sq_distance > limit_sq) ties.clear();
    return;
  }
  std::size_t kept = 0;
  for (const SurfaceHit& h : ties)
    if (h.sq_distance <= limit_sq) ties[kept++] = h;
  ties.resize(kept);
  if (kept < 2) return;
  std::sort(ties.begin(), ties.end(),
            [](const SurfaceHit& x, const SurfaceHit& y) { return x.face < y.face; });
}

}  // namespace detail
}  // namespace meshdev
