#include "metric/attributes.h"

#include <gtest/gtest.h>

#include "metric/color_space.h"
#include "metric/errors.h"
#include "metric/nearest_point.h"
#include "tests/support/shapes.h"

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
  double out[2];
  interpolate(*m.channel("t"), m, 0, {0.5, 0.25, 0.25}, kNoFace, out);
  EXPECT_DOUBLE_EQ(out[0], 0.25 * 10 + 0.25 * m.channel("t")->values[m.faces[0][2]]);
  interpolate(*m.channel("uv"), m, 1, {0, 1, 0}, kNoFace, out);  // corner 1 of face 1 = element 4
  EXPECT_EQ(out[0], 8.0);
  EXPECT_EQ(out[1], 9.0);
  interpolate(*m.channel("id"), m, 1, {0.2, 0.3, 0.5}, kNoFace, out);
  EXPECT_EQ(out[0], 7.0);
}

TEST(Attributes, NormalMeasuresUseUnitVectors) {
  const double x[3] = {2, 0, 0}, y[3] = {0, 0, 5};
  EXPECT_NEAR(attribute_distance(MeasureKind::kNormalAngle, x, y, 3), 90.0, 1e-12);
  EXPECT_NEAR(attribute_distance(MeasureKind::kNormalEuclidean, x, y, 3), std::sqrt(2.0), 1e-15);
  const double z[3] = {-1, 0, 0};
  EXPECT_NEAR(attribute_distance(MeasureKind::kNormalAngle, x, z, 3), 180.0, 1e-12);
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

}  // namespace
}  // namespace meshdev
