#include "metric/attributes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "metric/color_space.h"
#include "metric/errors.h"
#include "metric/io/write_png.h"
#include "metric/nearest_point.h"
#include "tests/support/shapes.h"
#include "tests/support/test_data.h"

namespace meshdev {
namespace {

TEST(Attributes, InterpolatesPerVertexPerCornerAndPerFace) {
  TriMesh m = test::square();  // faces {0,1,3}, {0,3,2}
  AttributeChannel& pv = m.add_channel("t", AttributeKind::kScalar, Storage::kPerVertex, 1);
  pv.values = {0, 10, 20, 30};
  AttributeChannel& pc = m.add_channel("uv", AttributeKind::kTexCoord, Storage::kPerCorner, 2);
  for (std::size_t i = 0; i < pc.values.size(); ++i) pc.values[i] = static_cast<double>(i);
  AttributeChannel& pf = m.add_channel("id", AttributeKind::kScalar, Storage::kPerFace, 1);
  pf.values = {5, 7};
  double out[4] = {0, 0, 0, -1};  // out[3]: must stay untouched
  interpolate(*m.channel("t"), m, 0, {0.5, 0.25, 0.25}, kNoFace, out);
  EXPECT_DOUBLE_EQ(out[0], 0.25 * 10 + 0.25 * m.channel("t")->values[m.faces[0][2]]);
  interpolate(*m.channel("uv"), m, 1, {0, 1, 0}, kNoFace, out);  // corner 1 of face 1 = element 4
  EXPECT_EQ(out[0], 8.0);
  EXPECT_EQ(out[1], 9.0);
  interpolate(*m.channel("id"), m, 1, {0.2, 0.3, 0.5}, kNoFace, out);
  EXPECT_EQ(out[0], 7.0);
  // Three components (normals, colours) take their own path: each component of each corner.
  AttributeChannel& rgb = m.add_channel("rgb", AttributeKind::kColor, Storage::kPerVertex, 3);
  for (std::size_t i = 0; i < rgb.values.size(); ++i) rgb.values[i] = static_cast<double>(i * i);
  interpolate(*m.channel("rgb"), m, 1, {0.5, 0.25, 0.25}, kNoFace, out);
  for (int k = 0; k < 3; ++k) {
    double want = 0;
    for (int c = 0; c < 3; ++c)
      want += (c == 0 ? 0.5 : 0.25) * rgb.values[3 * m.faces[1][c] + static_cast<std::size_t>(k)];
    EXPECT_EQ(out[k], want) << "component " << k;
  }
  EXPECT_EQ(out[3], -1.0);
}

TEST(Attributes, NormalMeasuresUseUnitVectors) {
  const double x[3] = {2, 0, 0}, y[3] = {0, 0, 5};
  EXPECT_NEAR(attribute_distance(MeasureKind::kNormalAngle, x, y, 3), 90.0, 1e-12);
  EXPECT_NEAR(attribute_distance(MeasureKind::kNormalEuclidean, x, y, 3), std::sqrt(2.0), 1e-15);
  const double z[3] = {-1, 0, 0};
  EXPECT_NEAR(attribute_distance(MeasureKind::kNormalAngle, x, z, 3), 180.0, 1e-12);
}

// The chord formula against rotations by known angles, tiny to 180 degrees, about random axes
// (built in long double, so the pairs carry the angle to far below the tolerance).
TEST(Attributes, NormalAngleIsTheRotationAngleFromTinyTo180Degrees) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss;
  const double angles[] = {0.0, 1e-9,   1e-6, 1e-3, 0.5, 1,       30,         60, 89.999,
                           90,  90.001, 120,  150,  179, 179.999, 179.999999, 180};
  for (int trial = 0; trial < 20; ++trial) {
    const long double n[3] = {gauss(rng), gauss(rng), gauss(rng)};
    long double a[3] = {gauss(rng), gauss(rng), gauss(rng)};
    const long double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const long double u[3] = {n[0] / nn, n[1] / nn, n[2] / nn};
    const long double ua = a[0] * u[0] + a[1] * u[1] + a[2] * u[2];
    for (int k = 0; k < 3; ++k) a[k] -= ua * u[k];  // a: perpendicular to u
    const long double na = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (long double& c : a) c /= na;
    for (double deg : angles) {
      const long double t = deg * 3.141592653589793238462643383279503L / 180;
      double x[3], y[3];
      for (int k = 0; k < 3; ++k) {
        x[k] = static_cast<double>(u[k]);
        y[k] = static_cast<double>(std::cos(t) * u[k] + std::sin(t) * a[k]);
      }
      const double got = attribute_distance(MeasureKind::kNormalAngle, x, y, 3);
      EXPECT_NEAR(got, deg, 1e-11) << "trial " << trial << ", " << deg << " degrees";
      EXPECT_GE(got, 0.0);
      EXPECT_LE(got, 180.0);
      // Symmetric in its arguments up to rounding, and independent of the vectors' lengths.
      EXPECT_NEAR(attribute_distance(MeasureKind::kNormalAngle, y, x, 3), got, 1e-11);
      const double y3[3] = {3 * y[0], 3 * y[1], 3 * y[2]};
      EXPECT_NEAR(attribute_distance(MeasureKind::kNormalAngle, x, y3, 3), got, 1e-11);
    }
  }
}

// Reference pair 1 of Sharma, Wu & Dalal (2005), Table 1: ΔE00 = 2.0425.
TEST(Attributes, DeltaE2000MatchesThePublishedTestData) {
  EXPECT_NEAR(delta_e2000({50, 2.6772, -79.7751}, {50, 0, -82.7485}), 2.0425, 1e-4);
  EXPECT_NEAR(delta_e2000({50, 2.5, 0}, {73, 25, -18}), 27.1492, 1e-4);  // pair 17
}

TEST(Attributes, WhiteIsL100AndBlackIsL0) {
  EXPECT_NEAR(srgb_to_lab({1, 1, 1}).x, 100.0, 1e-3);
  EXPECT_NEAR(srgb_to_lab({0, 0, 0}).x, 0.0, 1e-12);
}

TEST(Attributes, AutomaticPlanMeasuresSharedChannelsAndComputesNormals) {
  TriMesh a = test::icosphere(1), b = test::icosphere(1);
  a.add_channel("temperature", AttributeKind::kScalar, Storage::kPerVertex, 1);
  b.add_channel("temperature", AttributeKind::kScalar, Storage::kPerVertex, 1);
  a.add_channel("only_on_a", AttributeKind::kScalar, Storage::kPerVertex, 1);
  AttributePlan plan = plan_attributes(a, b, {}, "A", "B");
  std::vector<std::string> names;
  for (const Measure& m : plan.measures) names.push_back(m.name);
  EXPECT_EQ(names, (std::vector<std::string>{"geometry", "normal", "normal_angle", "temperature"}));
  EXPECT_NE(plan.normal_source.find("computed"), std::string::npos);
}

TEST(Attributes, RequestedAttributeMissingOnOneMeshIsAnError) {
  TriMesh a = test::tetrahedron(), b = test::tetrahedron();
  a.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3);
  AttributeOptions o;
  o.attributes = {"color"};
  try {
    plan_attributes(a, b, o, "a.ply", "b.ply");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("b.ply"), std::string::npos) << e.what();
  }
  o.normals = NormalSource::kFile;
  o.attributes = {"normal"};
  EXPECT_THROW(plan_attributes(a, b, o, "a", "b"), InvalidInput);
}

// A plan with a cache of A's values computes A's normals once per weighting and reads A's texture
// image once: later plans take them from the cache (A's image is not read again: the file can
// be gone), the same values as a plan without it.
TEST(Attributes, ReferenceCacheKeepsNormalsPerWeightingAndTheTexture) {
  const std::string dir = test::scratch_dir("ReferenceCacheKeepsNormals");
  TriMesh a = test::icosphere(1), b = test::translated(test::icosphere(1), {0.1, 0, 0});
  for (TriMesh* m : {&a, &b}) {
    AttributeChannel& uv =
        m->add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerVertex, 2);
    for (std::size_t i = 0; i < uv.values.size(); ++i)
      uv.values[i] = 0.01 * static_cast<double>(i % 97);
  }
  a.texture_file = dir + "/a.png";
  b.texture_file = dir + "/b.png";
  write_png(a.texture_file, Image(4, 2, {0.2, 0.4, 0.6}));
  write_png(b.texture_file, Image(2, 2, {0.9, 0.1, 0.1}));

  ReferenceAttributes cache;
  AttributeOptions o;
  o.attributes = {"normal", "texture"};
  const AttributePlan first = plan_attributes(a, b, o, "A", "B", &cache);
  ASSERT_EQ(cache.normals.size(), 1u);
  ASSERT_TRUE(cache.texture);
  EXPECT_EQ(cache.texture, first.a.texture);
  EXPECT_EQ(first.a.texture->width, 4);
  const AttributePlan plain = plan_attributes(a, b, o, "A", "B");
  ASSERT_EQ(first.a.computed.size(), 1u);
  EXPECT_EQ(first.a.computed[0].values, plain.a.computed[0].values);

  std::filesystem::remove(a.texture_file);
  EXPECT_THROW(plan_attributes(a, b, o, "A", "B"), IoError);
  const AttributePlan again = plan_attributes(a, b, o, "A", "B", &cache);
  EXPECT_EQ(again.a.texture, first.a.texture);
  EXPECT_NE(again.b.texture, plain.b.texture);  // B's image is read each time
  EXPECT_EQ(again.a.computed[0].values, plain.a.computed[0].values);
  EXPECT_EQ(cache.normals.size(), 1u);

  o.normals = NormalSource::kArea;
  const AttributePlan area = plan_attributes(a, b, o, "A", "B", &cache);
  EXPECT_EQ(cache.normals.size(), 2u);
  a.texture_file = b.texture_file;  // only the cache can give A's old image now
  const AttributePlan area_plain = plan_attributes(a, b, o, "A", "B");
  EXPECT_EQ(area.a.computed[0].values, area_plain.a.computed[0].values);
  EXPECT_NE(area.a.computed[0].values, first.a.computed[0].values);
  EXPECT_EQ(area.a.texture->width, 4);
}

}  // namespace
}  // namespace meshdev
