// Cohen's texture deviation (paper Eq. 2), the UV index it uses, and texture-colour deviation.
#include "metric/texture_deviation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "metric/attribute_deviation.h"
#include "metric/compare.h"
#include "metric/uv_index.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

// Per-vertex texture coordinates (x + du, y + dv): a planar parameterisation.
TriMesh with_planar_uv(TriMesh m, double du = 0.0, double dv = 0.0, double scale_u = 1.0) {
  AttributeChannel& uv =
      m.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerVertex, 2);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    uv.values[2 * v] = scale_u * m.positions[v].x + du;
    uv.values[2 * v + 1] = m.positions[v].y + dv;
  }
  return m;
}

CompareOptions cohen_options() {
  CompareOptions o;
  o.attributes.attributes = {"cohen"};
  o.sampling.step = 0.05;
  o.direction = Direction::kForward;
  return o;
}

std::size_t measure_index(const ComparisonResult& r, const std::string& name) {
  for (std::size_t m = 0; m < r.measures.size(); ++m)
    if (r.measures[m].name == name) return m;
  ADD_FAILURE() << "no measure " << name;
  return 0;
}

TEST(CohenTextureDeviation, IsZeroForIdenticalMeshes) {
  const TriMesh a = with_planar_uv(test::grid(6));
  const ComparisonResult r = compare_meshes(a, a, cohen_options());
  const std::size_t c = measure_index(r, "texcoord_cohen");
  EXPECT_EQ(measure_index(r, "texcoord"), c - 1);  // reported beside the texcoord deviation
  EXPECT_LE(r.forward->stats[c].max, 1e-12);
  EXPECT_EQ(r.forward->cohen_outside, 0u);
  EXPECT_EQ(r.forward->cohen_multiple, 0u);
}

TEST(CohenTextureDeviation, EqualsTheShiftOfShiftedTextureCoordinates) {
  // A = [0,1]^2 with uv = (x, y); B = [-1,2]^2 (same plane) with uv = (x + 0.13, y): the point of
  // B with uv (x, y) is (x - 0.13, y), so T = 0.13 everywhere.
  const double shift = 0.13;
  const TriMesh a = with_planar_uv(test::grid(5));
  const TriMesh b = with_planar_uv(test::translated(test::grid(9, 3.0), {-1, -1, 0}), shift);
  const ComparisonResult r = compare_meshes(a, b, cohen_options());
  const Statistics& s = r.forward->stats[measure_index(r, "texcoord_cohen")];
  EXPECT_NEAR(s.min, shift, 1e-12);
  EXPECT_NEAR(s.max, shift, 1e-12);
  EXPECT_NEAR(s.mean, shift, 1e-12);
  EXPECT_EQ(r.forward->cohen_outside, 0u);
  EXPECT_EQ(r.forward->cohen_multiple, 0u);
  // Geometry is identical where A lies: the geometric deviation is 0.
  EXPECT_LE(r.forward->stats[0].max, 1e-12);
}

TEST(CohenTextureDeviation, MeasuresGeometryWhenTheParameterisationIsKept) {
  // B = A lifted by 0.2 with the same UVs: Cohen's measure is the geometric change, while the
  // texture-coordinate attribute deviation is 0 (the paper's Fig. 5(d)-(f)).
  const TriMesh a = with_planar_uv(test::grid(4));
  const TriMesh b = test::translated(a, {0, 0, 0.2});
  const ComparisonResult r = compare_meshes(a, b, cohen_options());
  EXPECT_NEAR(r.forward->stats[measure_index(r, "texcoord_cohen")].max, 0.2, 1e-12);
  EXPECT_NEAR(r.forward->stats[measure_index(r, "texcoord_cohen")].min, 0.2, 1e-12);
  EXPECT_LE(r.forward->stats[measure_index(r, "texcoord")].max, 1e-12);
}

TEST(CohenTextureDeviation, CountsUvsOutsideTheOtherMeshAndUsesTheUvNearestPoint) {
  // B's u covers [0, 0.5] only: A's samples with u > 0.5 have no point on B.
  const TriMesh a = with_planar_uv(test::grid(4));
  const TriMesh b = with_planar_uv(test::grid(4), 0.0, 0.0, 0.5);
  const ComparisonResult r = compare_meshes(a, b, cohen_options());
  EXPECT_GT(r.forward->cohen_outside, 0u);
  EXPECT_LT(r.forward->cohen_outside, r.forward->samples);
  EXPECT_NEAR(r.forward->cohen_max_uv_gap, 0.5, 1e-12);
  // Inside: p'' = (2x, y), T = x <= 0.5; outside: p'' = (1, y), T = 1 - x < 0.5.
  EXPECT_LE(r.forward->stats[measure_index(r, "texcoord_cohen")].max, 0.5 + 1e-12);
}

TEST(CohenTextureDeviation, OverlappingChartsGiveTheSmallestDistanceAndAreCounted) {
  // B = A plus a copy 1 above with the same UVs: two points of B per UV, at 0 and 1.
  const TriMesh a = with_planar_uv(test::grid(3));
  TriMesh b = a;
  const TriMesh up = test::translated(a, {0, 0, 1});
  const auto offset = static_cast<std::uint32_t>(b.positions.size());
  b.positions.insert(b.positions.end(), up.positions.begin(), up.positions.end());
  for (Triangle t : up.faces) b.faces.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  AttributeChannel& uv = *b.channel("texcoord");
  const std::vector<double> first = uv.values;
  uv.values.insert(uv.values.end(), first.begin(), first.end());
  const ComparisonResult r = compare_meshes(a, b, cohen_options());
  EXPECT_LE(r.forward->stats[measure_index(r, "texcoord_cohen")].max, 1e-12);
  EXPECT_EQ(r.forward->cohen_multiple, r.forward->samples);
}

TEST(UvIndex, NearestMatchesBruteForceOnRandomTriangles) {
  const TriMesh soup = test::random_soup(300, 7, 0.1);
  AttributeChannel uv{"texcoord", AttributeKind::kTexCoord, Storage::kPerVertex, 2, {}};
  for (const Vec3& p : soup.positions) uv.values.insert(uv.values.end(), {p.x, p.y});
  const UvIndex index(soup, uv);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> d(-0.5, 1.5);
  for (int q = 0; q < 300; ++q) {
    const double u = d(rng), v = d(rng);
    double best = 1e300;  // brute force: distance to every UV triangle (inside = 0, else edges)
    for (const Triangle& t : soup.faces) {
      const double* p[3] = {uv.element(t[0]), uv.element(t[1]), uv.element(t[2])};
      for (int e = 0; e < 3; ++e) {
        const double* x = p[e];
        const double* y = p[(e + 1) % 3];
        const double du = y[0] - x[0], dv = y[1] - x[1], len2 = du * du + dv * dv;
        const double s =
            len2 > 0 ? std::clamp(((u - x[0]) * du + (v - x[1]) * dv) / len2, 0.0, 1.0) : 0.0;
        best = std::min(best, std::hypot(x[0] + s * du - u, x[1] + s * dv - v));
      }
    }
    std::vector<UvHit> hits;
    index.containing(u, v, hits);
    const UvHit h = index.nearest(u, v);
    if (!hits.empty()) {
      EXPECT_EQ(h.uv_distance, 0.0);
    } else {
      EXPECT_NEAR(h.uv_distance, best, 1e-12) << u << ' ' << v;
    }
  }
}

TEST(TextureColorDeviation, ComparesTheImagesAtTheUvsOfPAndItsNearestPoint) {
  const TriMesh m = with_planar_uv(test::grid(3));
  auto blue = std::make_shared<const Image>(4, 4, Vec3{0, 0, 1});
  auto red = std::make_shared<const Image>(4, 4, Vec3{1, 0, 0});
  const std::vector<Measure> measures = {
      {"geometry", MeasureKind::kGeometry, "", ""},
      {"texture_color", MeasureKind::kTextureColorRgb, "texcoord", ""},
      {"texture_color_de76", MeasureKind::kTextureColorDeltaE76, "texcoord", ""}};
  SamplingOptions so;
  so.step = 0.1;
  const SampleSet samples = sample_surface(m, so, 1.0);
  const std::unique_ptr<NearestPointIndex> index =
      make_nearest_point_index(m, IndexKind::kBvh, TieOptions{});
  PreparedMesh a{&m, {}, blue};
  PreparedMesh same{&m, {}, blue};
  PreparedMesh other{&m, {}, red};
  const SampleDeviations zero = compute_deviations(samples, a, same, *index, measures);
  const SampleDeviations full = compute_deviations(samples, a, other, *index, measures);
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    EXPECT_EQ(zero.values[1][i], 0.0);
    EXPECT_NEAR(full.values[1][i], std::sqrt(2.0), 1e-12);
    EXPECT_GT(full.values[2][i], 100.0);  // blue vs red: ΔE*ab ≈ 176
  }
}

TEST(TextureImage, BilinearHitsTexelCentresWrapsAndFlipsV) {
  Image img(2, 2, {0, 0, 0});
  img.set(0, 0, {1, 0, 0});                                      // top-left
  img.set(1, 1, {0, 0, 1});                                      // bottom-right
  EXPECT_EQ(sample_bilinear(img, 0.25, 0.75), (Vec3{1, 0, 0}));  // v = 1 is the top row
  EXPECT_EQ(sample_bilinear(img, 0.75, 0.25), (Vec3{0, 0, 1}));
  EXPECT_EQ(sample_bilinear(img, 1.25, -0.25), (Vec3{1, 0, 0}));  // repeat
  const Vec3 mid = sample_bilinear(img, 0.5, 0.5);
  EXPECT_NEAR(mid.x, 0.25, 1e-12);
  EXPECT_NEAR(mid.z, 0.25, 1e-12);
}

}  // namespace
}  // namespace meshdev
