#include "metric/nearest_point.h"

#include <gtest/gtest.h>

#include <random>

#include "metric/errors.h"
#include "metric/nearest_point_brute.h"
#include "metric/triangle_bvh.h"
#include "metric/triangle_grid.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

void expect_same(const std::vector<SurfaceHit>& x, const std::vector<SurfaceHit>& y) {
  ASSERT_EQ(x.size(), y.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(x[i].face, y[i].face);
    EXPECT_EQ(x[i].sq_distance, y[i].sq_distance);
    EXPECT_EQ(x[i].bary, y[i].bary);
    EXPECT_EQ(x[i].feature, y[i].feature);
  }
}

// The BVH must return exactly the oracle's distance and tie set, on soups with degenerate faces.
TEST(NearestPoint, BvhEqualsBruteForceOnRandomSoups) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    TriMesh soup = test::random_soup(400, seed);
    TriangleBvh bvh(soup);
    NearestPointBrute brute(soup);
    std::mt19937_64 rng(seed * 7919);
    std::uniform_real_distribution<double> u(-0.3, 1.3);
    std::vector<SurfaceHit> tb, tf;
    for (int q = 0; q < 500; ++q) {
      const Vec3 p{u(rng), u(rng), u(rng)};
      const double db = bvh.find(p, {}, tb);
      const double df = brute.find(p, {}, tf);
      ASSERT_EQ(db, df) << "seed " << seed << " query " << q;
      expect_same(tb, tf);
    }
  }
}

TEST(NearestPoint, BvhEqualsBruteForceOnASphereWithStartHints) {
  TriMesh sphere = test::icosphere(3);
  TriangleBvh bvh(sphere);
  NearestPointBrute brute(sphere);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::vector<SurfaceHit> tb, tf;
  std::uint32_t previous = kNoFace;
  for (int q = 0; q < 500; ++q) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    QueryHint hint;
    hint.start_face = previous;
    ASSERT_EQ(bvh.find(p, hint, tb), brute.find(p, {}, tf));
    expect_same(tb, tf);
    previous = tb.front().face;
  }
}

// The grid's fast path and its BVH fallback must both give exactly the oracle's answer: queries
// on and near the surface (fast path), far away (fallback) and outside the grid.
TEST(NearestPoint, GridEqualsBruteForceNearAndFarFromTheSurface) {
  for (std::uint64_t seed : {4u, 5u}) {
    TriMesh soup = test::random_soup(600, seed);
    TriMesh sphere = test::icosphere(3);
    for (const TriMesh* m : {&soup, &sphere}) {
      TriangleGrid grid(*m);
      NearestPointBrute brute(*m);
      std::mt19937_64 rng(seed);
      std::uniform_real_distribution<double> u(0.0, 1.0), n(-1e-3, 1e-3), far(-3.0, 3.0);
      std::vector<SurfaceHit> tg, tf;
      for (int q = 0; q < 1500; ++q) {
        Vec3 p;
        if (q % 3 == 2) {
          p = {far(rng), far(rng), far(rng)};
        } else {  // a point on a random face, nudged off it
          const Triangle& t = m->faces[rng() % m->faces.size()];
          double a = u(rng), b = u(rng);
          if (a + b > 1) a = 1 - a, b = 1 - b;
          p = m->positions[t[0]] + a * (m->positions[t[1]] - m->positions[t[0]]) +
              b * (m->positions[t[2]] - m->positions[t[0]]);
          if (q % 3 == 1) p = p + Vec3{n(rng), n(rng), n(rng)};
        }
        ASSERT_EQ(grid.find(p, {}, tg), brute.find(p, {}, tf)) << "seed " << seed << " query " << q;
        expect_same(tg, tf);
      }
    }
  }
}

TEST(NearestPoint, QueryAtASharedVertexReturnsEveryIncidentFaceAsATie) {
  TriMesh sphere = test::icosahedron();
  TriangleBvh bvh(sphere);
  std::vector<SurfaceHit> ties;
  EXPECT_EQ(bvh.find(sphere.positions[0], {}, ties), 0.0);
  EXPECT_EQ(ties.size(), 5u);  // icosahedron vertices have valence 5
  for (const SurfaceHit& h : ties) EXPECT_EQ(h.feature, Feature::kVertex);
}

TEST(NearestPoint, SourceHintMakesASampleOnAnIdenticalTriangleExactlyZero) {
  TriMesh m = test::icosahedron();
  TriangleBvh bvh(m);
  const Triangle& t = m.faces[3];
  const Vec3 corners[3] = {m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]};
  QueryHint hint;
  hint.source = corners;
  hint.source_bary = {0.2, 0.3, 0.5};
  const Vec3 p = 0.2 * corners[0] + 0.3 * corners[1] + 0.5 * corners[2];
  std::vector<SurfaceHit> ties;
  EXPECT_EQ(bvh.find(p, hint, ties), 0.0);
  ASSERT_EQ(ties.size(), 1u);
  EXPECT_EQ(ties[0].face, 3u);
  EXPECT_EQ(ties[0].bary, hint.source_bary);
}

TEST(NearestPoint, TargetWithoutFacesIsRejected) {
  TriMesh cloud;
  cloud.positions = {{0, 0, 0}};
  EXPECT_THROW(make_nearest_point_index(cloud, IndexKind::kBvh), InvalidInput);
}

}  // namespace
}  // namespace meshdev
