#include "metric/closest_point_triangle.h"

#include <algorithm>

namespace meshdev {
namespace {

// Closest point on segment (a, b); writes t in [0, 1] with point = a + t (b - a) and the
// squared distance.
Vec3 closest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b, double& t, double& sq) {
  const Vec3 ab = b - a, ap = p - a;
  const double len2 = squared_norm(ab);
  t = len2 > 0.0 ? std::clamp(dot(ap, ab) / len2, 0.0, 1.0) : 0.0;
  if (t == 0.0) {
    sq = squared_norm(ap);
    return a;
  }
  if (t == 1.0) {
    sq = squared_norm(p - b);
    return b;
  }
  sq = squared_norm(ap - t * ab);
  return a + t * ab;
}

}  // namespace

namespace detail {

// A degenerate triangle as the union of its edges: best of the three segments.
TriangleHit closest_on_degenerate(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  double t = 0, sq = 0;
  Vec3 q = closest_on_segment(p, a, b, t, sq);
  TriangleHit best = make_hit(q, sq, 1.0 - t, t, 0.0);
  q = closest_on_segment(p, b, c, t, sq);
  TriangleHit h = make_hit(q, sq, 0.0, 1.0 - t, t);
  if (h.sq_distance < best.sq_distance) best = h;
  q = closest_on_segment(p, c, a, t, sq);
  h = make_hit(q, sq, t, 0.0, 1.0 - t);
  if (h.sq_distance < best.sq_distance) best = h;
  return best;
}

}  // namespace detail

const char* feature_name(Feature f) {
  switch (f) {
    case Feature::kVertex:
      return "vertex";
    case Feature::kEdge:
      return "edge";
    case Feature::kFace:
      return "face";
  }
  return "?";
}

}  // namespace meshdev
