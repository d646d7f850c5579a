#pragma once
// Exact closest point on one triangle, in double, with its barycentric coordinates and the
// feature (vertex, edge or face interior) it lies on.
#include <array>
#include <cstdint>

#include "metric/vec3.h"

namespace meshdev {

// Which part of a triangle the closest point lies on.
enum class Feature : std::uint8_t { kVertex = 0, kEdge = 1, kFace = 2 };

const char* feature_name(Feature f);

struct TriangleHit {
  double sq_distance = 0;  // squared Euclidean distance |p - point|^2 (absolute units^2)
  Vec3 point;              // closest point on the triangle
  std::array<double, 3> bary{1, 0, 0};  // point = bary[0] a + bary[1] b + bary[2] c, sums to 1
  Feature feature = Feature::kVertex;   // kVertex: two bary are 0; kEdge: one is 0; kFace: none
};

namespace detail {
// `sq` is computed by the caller from vectors relative to the triangle (p - a - t ab, not
// p - point), so its rounding error scales with the triangle, not with the coordinates' distance
// from the origin.
inline TriangleHit make_hit(const Vec3& q, double sq, double b0, double b1, double b2) {
  TriangleHit h;
  h.point = q;
  h.sq_distance = sq;
  h.bary = {b0, b1, b2};
  int zeros = (b0 == 0.0) + (b1 == 0.0) + (b2 == 0.0);
  h.feature = zeros >= 2 ? Feature::kVertex : (zeros == 1 ? Feature::kEdge : Feature::kFace);
  return h;
}

// A degenerate triangle as the union of its three edges: the best of the three segments.
TriangleHit closest_on_degenerate(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);
}  // namespace detail

// The part of closest_point_on_triangle that does not depend on the point or the corners'
// storage: the edges ab and ac, the normal n = ab x ac, |n|^2, and whether the triangle is
// degenerate. O(1).
struct TriangleFrame {
  Vec3 ab, ac, n;
  double n2 = 0;
  bool degenerate = false;
};
[[gnu::always_inline]] inline TriangleFrame triangle_frame(const Vec3& a, const Vec3& b,
                                                           const Vec3& c) {
  TriangleFrame t;
  t.ab = b - a;
  t.ac = c - a;
  const double ab2 = squared_norm(t.ab), ac2 = squared_norm(t.ac);
  t.n = cross(t.ab, t.ac);
  t.n2 = squared_norm(t.n);
  t.degenerate =
      ab2 == 0.0 || ac2 == 0.0 || squared_norm(c - b) == 0.0 || !(t.n2 > 1e-12 * ab2 * ac2);
  return t;
}

// closest_point_on_triangle(p, a, b, c) below, from the corners and their frame
// (triangle_frame(a, b, c)): bit for bit the same (the same operations on the same values). The
// corners are read where they are (a mesh's positions), so only the frame need be held in
// registers. Always inlined: GCC 12 kept it out of line (1.1M calls for 1M queries on torus100k
// -> torus1m), the call returned the hit through memory, and a frame passed to it was first
// copied to the stack (an exact test took 420 instructions in the face region, 348 inlined
// without the copy; docs/performance-log.md §3).
[[gnu::always_inline]] inline TriangleHit closest_point_on_triangle(const Vec3& p, const Vec3& a,
                                                                    const Vec3& b, const Vec3& c,
                                                                    const TriangleFrame& t) {
  const Vec3 &ab = t.ab, &ac = t.ac, &n = t.n;
  const double n2 = t.n2;
  if (t.degenerate) return detail::closest_on_degenerate(p, a, b, c);
  // Vertex region A.
  const Vec3 ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return detail::make_hit(a, squared_norm(ap), 1, 0, 0);
  // Vertex region B.
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return detail::make_hit(b, squared_norm(bp), 0, 1, 0);
  // Edge region AB. Each edge's parameter is num / den with 0 <= num <= den, and den is |edge|^2
  // in exact arithmetic. Where it rounds to 0 (a query ~1e95 times farther than the edge is
  // long: both projections flattened to 0, found by fuzz_nearest_point) the region test itself
  // is noise, so that edge's region is not taken (and 0 / 0 never computed).
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) {
    const double v = d1 / (d1 - d3);
    return detail::make_hit(a + v * ab, squared_norm(ap - v * ab), 1.0 - v, v, 0);
  }
  // Vertex region C.
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return detail::make_hit(c, squared_norm(cp), 0, 0, 1);
  // Edge region AC.
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) {
    const double w = d2 / (d2 - d6);
    return detail::make_hit(a + w * ac, squared_norm(ap - w * ac), 1.0 - w, 0, w);
  }
  // Edge region BC.
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return detail::make_hit(b + w * (c - b), squared_norm(bp - w * (c - b)), 0, 1.0 - w, w);
  }
  // Face interior: the distance to the plane, exactly 0 for a point in the plane. (va + vb + vc
  // = |n|^2 > 0 here; rounding that left no positive sum leaves the triangle as its edges.)
  if (!(va + vb + vc > 0.0)) return detail::closest_on_degenerate(p, a, b, c);
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  const double h = dot(ap, n);
  return detail::make_hit(a + v * ab + w * ac, h * h / n2, 1.0 - v - w, v, w);
}

// Closest point to p on triangle (a, b, c) by the Voronoi-region walk of Ericson, "Real-Time
// Collision Detection" (2005) §5.1.5. Degenerate triangles (a zero-length edge, or |ab x ac|^2 at
// most 1e-12 |ab|^2 |ac|^2, i.e. an angle below 1e-6 rad) are treated as the union of their three
// edges, so the result is never NaN; the distance error this allows is below the inradius (< 1e-6
// of the longest edge). A point bitwise equal to a vertex gets distance exactly 0. O(1), no
// allocation. Inline: it runs once or more per query, and a call returned the hit through memory,
// which the caller then read back with wider loads than the callee's stores (a stall per field).
inline TriangleHit closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                             const Vec3& c) {
  return closest_point_on_triangle(p, a, b, c, triangle_frame(a, b, c));
}

}  // namespace meshdev
