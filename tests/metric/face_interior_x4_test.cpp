#include "metric/face_interior_x4.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "metric/closest_point_triangle.h"
#include "metric/plane_bounds.h"

namespace meshdev {
namespace {

bool same_bits(double x, double y) {
  return std::memcmp(&x, &y, sizeof x) == 0;
}

// Lane l of a face_interior_x4 answer against closest_point_on_triangle, bit for bit.
void expect_lane_equals_one_triangle(const SurfaceHit& lane, const Vec3& p, const Vec3& a,
                                     const Vec3& b, const Vec3& c) {
  const TriangleHit one = closest_point_on_triangle(p, a, b, c);
  EXPECT_TRUE(same_bits(lane.sq_distance, one.sq_distance))
      << lane.sq_distance << " vs " << one.sq_distance;
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(same_bits(lane.bary[k], one.bary[k])) << "bary " << k;
    EXPECT_TRUE(same_bits(lane.point[k], one.point[k])) << "point " << k;
  }
  EXPECT_EQ(lane.feature, one.feature);
}

// Random triangles (a tenth of them degenerate: a repeated corner or three collinear ones) at
// scales from 1e-6 to 1e6 and offsets up to 1e8, with points near their interior, beyond their
// edges and corners, and far away: every lane the kernel answers is the one-triangle answer bit
// for bit, and the points over the interior of proper triangles are answered.
TEST(FaceInteriorX4, AnsweredLanesEqualTheOneTriangleWalkBitForBit) {
  if (simd_level() == SimdLevel::kBaseline)
    GTEST_SKIP() << "the CPU (or MESHDEV_SIMD=baseline) has no AVX2: the kernel is never entered";
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  std::size_t answered = 0, interior = 0, interior_answered = 0;
  for (int round = 0; round < 20000; ++round) {
    Vec3 p[4], a[4], b[4], c[4];
    bool over_interior[4];
    for (int l = 0; l < 4; ++l) {
      const double scale = std::pow(10.0, 12.0 * unit(rng) - 6.0);
      const Vec3 offset = std::pow(10.0, 8.0 * unit(rng)) * Vec3{u(rng), u(rng), u(rng)};
      a[l] = offset + scale * Vec3{u(rng), u(rng), u(rng)};
      b[l] = offset + scale * Vec3{u(rng), u(rng), u(rng)};
      c[l] = offset + scale * Vec3{u(rng), u(rng), u(rng)};
      const int kind = round % 10;
      if (kind == 0) c[l] = b[l];                        // a repeated corner
      if (kind == 1) c[l] = a[l] + 2.0 * (b[l] - a[l]);  // collinear corners
      // Barycentrics: inside the triangle for most points, beyond an edge or a corner for others.
      double v = unit(rng), w = unit(rng);
      over_interior[l] = kind >= 2 && round % 3 != 0;
      if (over_interior[l] && v + w > 1.0) {
        v = 1.0 - v;
        w = 1.0 - w;
      }
      if (!over_interior[l]) {
        v = 3.0 * u(rng);
        w = 3.0 * u(rng);
      }
      const Vec3 n = cross(b[l] - a[l], c[l] - a[l]);
      const double height = round % 7 == 0 ? 0.0 : u(rng) * (round % 5 == 0 ? 1e3 : 0.1);
      p[l] = a[l] + v * (b[l] - a[l]) + w * (c[l] - a[l]) +
             (norm(n) > 0.0 ? height / std::sqrt(norm(n)) : 0.0) * n;
    }
    const Vec3 *pp[4], *pa[4], *pb[4], *pc[4];
    SurfaceHit hits[4];
    SurfaceHit* out[4];
    for (int l = 0; l < 4; ++l) {
      pp[l] = &p[l];
      pa[l] = &a[l];
      pb[l] = &b[l];
      pc[l] = &c[l];
      out[l] = &hits[l];
    }
    const unsigned done = detail::face_interior_x4(pp, pa, pb, pc, out);
    ASSERT_EQ(done & ~0xfu, 0u);
    for (int l = 0; l < 4; ++l) {
      const bool is_done = (done >> l & 1u) != 0;
      answered += is_done;
      interior += over_interior[l];
      interior_answered += over_interior[l] && is_done;
      if (!is_done) continue;
      SCOPED_TRACE(testing::Message() << "round " << round << ", lane " << l);
      expect_lane_equals_one_triangle(hits[l], p[l], a[l], b[l], c[l]);
      if (HasFailure()) return;
    }
  }
  // Points over the interior are the kernel's to answer (a few lie on an edge's side by
  // rounding, and slivers count as degenerate); the others mostly are not.
  EXPECT_GT(interior_answered, interior * 95 / 100);
  EXPECT_LT(answered - interior_answered, (80000 - interior) / 2);
}

// Lanes left to the one-triangle walk: a degenerate triangle, a point beyond a corner, beyond an
// edge, and a NaN point; beside them a point over the interior is answered.
TEST(FaceInteriorX4, VertexEdgeDegenerateAndNaNLanesAreLeftToTheWalk) {
  if (simd_level() == SimdLevel::kBaseline)
    GTEST_SKIP() << "the CPU (or MESHDEV_SIMD=baseline) has no AVX2: the kernel is never entered";
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Vec3 inside{0.25, 0.25, 0.5}, corner{-1, -1, 0.1}, edge{0.5, -1, 0}, nan_point{nan, 0, 0};
  const Vec3 flat_c{2, 0, 0};  // a, b, flat_c collinear
  {
    const Vec3 *p[4] = {&inside, &corner, &edge, &nan_point}, *pa[4] = {&a, &a, &a, &a},
               *pb[4] = {&b, &b, &b, &b}, *pc[4] = {&c, &c, &c, &c};
    SurfaceHit hits[4];
    SurfaceHit* out[4] = {&hits[0], &hits[1], &hits[2], &hits[3]};
    EXPECT_EQ(detail::face_interior_x4(p, pa, pb, pc, out), 1u);
    EXPECT_EQ(hits[0].sq_distance, 0.25);
    EXPECT_EQ(hits[0].feature, Feature::kFace);
    expect_lane_equals_one_triangle(hits[0], inside, a, b, c);
  }
  {
    const Vec3 *p[4] = {&inside, &inside, &inside, &inside}, *pa[4] = {&a, &a, &a, &a},
               *pb[4] = {&b, &b, &b, &b}, *pc[4] = {&flat_c, &c, &flat_c, &c};
    SurfaceHit hits[4];
    SurfaceHit* out[4] = {&hits[0], &hits[1], &hits[2], &hits[3]};
    EXPECT_EQ(detail::face_interior_x4(p, pa, pb, pc, out), 0b1010u);
  }
}

}  // namespace
}  // namespace meshdev
