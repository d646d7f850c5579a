#include "metric/closest_point_triangle.h"

#include <algorithm>

namespace meshdev {
namespace {

// `sq` is computed by the caller from vectors relative to the triangle (p - a - t ab, not
// p - point), so its rounding error scales with the triangle, not with the coordinates' distance
// from the origin.
TriangleHit make_hit(const Vec3& q, double sq, double b0, double b1, double b2) {
  TriangleHit h;
  h.point = q;
  h.sq_distance = sq;
  h.bary = {b0, b1, b2};
  int zeros = (b0 == 0.0) + (b1 == 0.0) + (b2 == 0.0);
  h.feature = zeros >= 2 ? Feature::kVertex : (zeros == 1 ? Feature::kEdge : Feature::kFace);
  return h;
}

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

}  // namespace

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

TriangleHit closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a;
  const double ab2 = squared_norm(ab), ac2 = squared_norm(ac);
  const Vec3 n = cross(ab, ac);
  const double n2 = squared_norm(n);
  if (ab2 == 0.0 || ac2 == 0.0 || squared_norm(c - b) == 0.0 || !(n2 > 1e-12 * ab2 * ac2))
    return closest_on_degenerate(p, a, b, c);

  // Vertex region A.
  const Vec3 ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return make_hit(a, squared_norm(ap), 1, 0, 0);
  // Vertex region B.
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return make_hit(b, squared_norm(bp), 0, 1, 0);
  // Edge region AB. Each edge's parameter is num / den with 0 <= num <= den, and den is |edge|^2
  // in exact arithmetic. Where it rounds to 0 (a query ~1e95 times farther than the edge is
  // long: both projections flattened to 0, found by fuzz_nearest_point) the region test itself
  // is noise, so that edge's region is not taken (and 0 / 0 never computed).
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) {
    const double v = d1 / (d1 - d3);
    return make_hit(a + v * ab, squared_norm(ap - v * ab), 1.0 - v, v, 0);
  }
  // Vertex region C.
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return make_hit(c, squared_norm(cp), 0, 0, 1);
  // Edge region AC.
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) {
    const double w = d2 / (d2 - d6);
    return make_hit(a + w * ac, squared_norm(ap - w * ac), 1.0 - w, 0, w);
  }
  // Edge region BC.
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return make_hit(b + w * (c - b), squared_norm(bp - w * (c - b)), 0, 1.0 - w, w);
  }
  // Face interior: the distance to the plane, exactly 0 for a point in the plane. (va + vb + vc
  // = |n|^2 > 0 here; rounding that left no positive sum leaves the triangle as its edges.)
  if (!(va + vb + vc > 0.0)) return closest_on_degenerate(p, a, b, c);
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  const double h = dot(ap, n);
  return make_hit(a + v * ab + w * ac, h * h / n2, 1.0 - v - w, v, w);
}

}  // namespace meshdev
