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

// Closest point to p on triangle (a, b, c) by the Voronoi-region walk of Ericson, "Real-Time
// Collision Detection" (2005) §5.1.5. Degenerate triangles (a zero-length edge, or |ab x ac|^2 at
// most 1e-12 |ab|^2 |ac|^2, i.e. an angle below 1e-6 rad) are treated as the union of their three
// edges, so the result is never NaN; the distance error this allows is below the inradius (< 1e-6
// of the longest edge). A point bitwise equal to a vertex gets distance exactly 0. O(1), no
// allocation.
TriangleHit closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace meshdev
