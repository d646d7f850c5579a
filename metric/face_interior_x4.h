#pragma once
// The exact closest points of four queries on four triangles at once, where they lie in the
// triangles' interiors: the face region of closest_point_on_triangle (metric/
// closest_point_triangle.h), in the four double lanes of AVX registers. Each lane performs exactly
// the one-triangle path's operations in their order (triangle_frame, the Voronoi walk's dot
// products and region tests, the face region's barycentrics, point and squared distance), and
// IEEE add, subtract, multiply and divide are correctly rounded at any width, so a lane's answer is
// bit for bit the one-triangle answer. Compiled for AVX2 in its own translation unit (without
// FMA, under the library's -ffp-contract=off) and entered only where simd_level() (metric/
// plane_bounds.h) is not kBaseline.
#include <cstdint>

#include "metric/nearest_point.h"

namespace meshdev::detail {

// For each lane l: if the closest point of *p[l] on the triangle (*a[l], *b[l], *c[l]) lies in the
// triangle's interior region (not on a vertex's or an edge's region; the triangle not degenerate
// by triangle_frame's test), sets bit l of the result and writes that closest point to *out[l]:
// its squared distance, barycentrics, point and feature (not its face). Writes the other lanes'
// fields too, with values to be discarded: they are for closest_point_on_triangle. Lanes may
// repeat a query (the same pointers). All absolute units. Preconditions: the CPU runs AVX2. O(1).
unsigned face_interior_x4(const Vec3* const p[4], const Vec3* const a[4], const Vec3* const b[4],
                          const Vec3* const c[4], SurfaceHit* const out[4]);

}  // namespace meshdev::detail
