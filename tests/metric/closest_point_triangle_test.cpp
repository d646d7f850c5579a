#include "metric/closest_point_triangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace meshdev {
namespace {

const Vec3 kA{0, 0, 0}, kB{1, 0, 0}, kC{0, 1, 0};

TEST(ClosestPointTriangle, PointAboveInteriorProjectsOntoFace) {
  TriangleHit h = closest_point_on_triangle({0.25, 0.25, 2.0}, kA, kB, kC);
  EXPECT_EQ(h.feature, Feature::kFace);
  EXPECT_NEAR(std::sqrt(h.sq_distance), 2.0, 1e-15);
  EXPECT_NEAR(h.bary[0], 0.5, 1e-15);
  EXPECT_NEAR(h.bary[1], 0.25, 1e-15);
  EXPECT_NEAR(h.bary[2], 0.25, 1e-15);
}

TEST(ClosestPointTriangle, VertexRegionsReturnTheVertexExactly) {
  TriangleHit h = closest_point_on_triangle({-1, -1, 0.5}, kA, kB, kC);
  EXPECT_EQ(h.feature, Feature::kVertex);
  EXPECT_EQ(h.point, kA);
  EXPECT_EQ(h.bary[0], 1.0);
  h = closest_point_on_triangle({3, -0.5, 0}, kA, kB, kC);
  EXPECT_EQ(h.point, kB);
  h = closest_point_on_triangle({-0.1, 4, 0}, kA, kB, kC);
  EXPECT_EQ(h.point, kC);
}

TEST(ClosestPointTriangle, EdgeRegionsGiveEdgeFeatureWithOneZeroBarycentric) {
  TriangleHit h = closest_point_on_triangle({0.5, -1, 0}, kA, kB, kC);  // below AB
  EXPECT_EQ(h.feature, Feature::kEdge);
  EXPECT_EQ(h.bary[2], 0.0);
  EXPECT_NEAR(h.sq_distance, 1.0, 1e-15);
  h = closest_point_on_triangle({1, 1, 0}, kA, kB, kC);  // beyond BC
  EXPECT_EQ(h.feature, Feature::kEdge);
  EXPECT_EQ(h.bary[0], 0.0);
  EXPECT_NEAR(h.sq_distance, 0.5, 1e-15);
}

TEST(ClosestPointTriangle, QueryOnAVertexIsExactlyZero) {
  TriangleHit h =
      closest_point_on_triangle({0.3, 0.7, 0.1}, {0.3, 0.7, 0.1}, {2, 3, 4}, {5, -1, 2});
  EXPECT_EQ(h.sq_distance, 0.0);
}

TEST(ClosestPointTriangle, DegenerateTrianglesNeverGiveNaN) {
  const Vec3 p{0.3, 0.8, 0.2};
  // Collinear corners, a repeated corner, and all corners equal.
  for (auto [a, b, c] : {std::tuple<Vec3, Vec3, Vec3>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}},
                         {{0, 0, 0}, {0, 0, 0}, {1, 1, 0}},
                         {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}}) {
    TriangleHit h = closest_point_on_triangle(p, a, b, c);
    ASSERT_TRUE(std::isfinite(h.sq_distance));
    ASSERT_TRUE(is_finite(h.point));
    EXPECT_NEAR(h.bary[0] + h.bary[1] + h.bary[2], 1.0, 1e-15);
    EXPECT_NEAR(h.sq_distance, squared_norm(p - h.point), 1e-15);
  }
  // Collinear: the distance to the segment from (0,0,0) to (2,0,0).
  TriangleHit h = closest_point_on_triangle(p, {0, 0, 0}, {1, 0, 0}, {2, 0, 0});
  EXPECT_NEAR(h.sq_distance, 0.8 * 0.8 + 0.2 * 0.2, 1e-15);
}

// Found by fuzz_nearest_point: a query 1e95 times farther than edge AB is long, off its side,
// rounds both of AB's projections (d1, d3) to 0: the parameter was 0 / 0 = NaN, and even
// guarded, AB's region test was noise. The nearest point lies on the long edges, at distance
// sqrt(1.25) s from p = (s, -s, s / 2) (the triangle hugs the x axis).
TEST(ClosestPointTriangle, FarQueryOffAShortEdge) {
  const Vec3 a{-7.5, -7.5, 0}, b{0, 0, 0}, c{1e100, 4.6875, -5.0625};
  for (double s : {1e96, 5e96, 9e96}) {
    const Vec3 p{s, -s, 0.5 * s};
    const TriangleHit h = closest_point_on_triangle(p, a, b, c);
    ASSERT_TRUE(is_finite(h.point)) << s;
    for (double x : h.bary) ASSERT_TRUE(std::isfinite(x)) << s;
    EXPECT_NEAR(std::sqrt(h.sq_distance), std::sqrt(1.25) * s, 1e-9 * s);
  }
}

// The kernel against a dense brute-force search over the triangle's barycentric grid.
TEST(ClosestPointTriangle, NeverFartherThanAnyPointOfTheTriangle) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    const Vec3 p{u(rng), u(rng), u(rng)};
    TriangleHit h = closest_point_on_triangle(p, a, b, c);
    const Vec3 q = h.bary[0] * a + h.bary[1] * b + h.bary[2] * c;
    EXPECT_NEAR(norm(q - h.point), 0.0, 1e-12);
    for (int i = 0; i <= 40; ++i)
      for (int j = 0; i + j <= 40; ++j) {
        const double s = i / 40.0, t = j / 40.0;
        const Vec3 x = (1 - s - t) * a + s * b + t * c;
        ASSERT_LE(h.sq_distance, squared_norm(p - x) + 1e-12);
      }
  }
}

}  // namespace
}  // namespace meshdev
