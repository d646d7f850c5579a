#include "metric/colored_mesh.h"

#include <gtest/gtest.h>

#include <cmath>

#include "metric/errors.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

// A tilted plane against the flat one: the deviation grows with x, and so must the colour
// (blue at x = 0, red at x = 1) and the quality value.
TEST(ColoredMesh, ColoursFollowTheDeviationAcrossTheMesh) {
  TriMesh a = test::grid(10);
  for (Vec3& p : a.positions) p.z = 0.1 * p.x;
  TriMesh b = test::grid(3);
  CompareOptions o;
  o.direction = Direction::kForward;
  o.keep_samples = true;
  ComparisonResult r = compare_meshes(a, b, o);
  TriMesh colored = color_by_deviation(a, *r.forward, {});
  const AttributeChannel* q = colored.channel("quality");
  const AttributeChannel* c = colored.channel("color");
  ASSERT_NE(q, nullptr);
  ASSERT_NE(c, nullptr);
  for (std::size_t v = 0; v < a.num_vertices(); ++v) {
    EXPECT_NEAR(q->values[v], 0.1 * a.positions[v].x, 1e-12);  // height above B
    if (a.positions[v].x == 0.0) {
      EXPECT_EQ(c->values[3 * v + 2], 1.0);  // blue
    }
    if (a.positions[v].x == 1.0) {
      EXPECT_EQ(c->values[3 * v], 1.0);  // red
    }
  }
}

// A fixed range is checked (colormap.h, check_color_range); the data's own range may be empty
// (identical meshes: every deviation 0) and gives the middle colour.
TEST(ColoredMesh, AFixedRangeIsCheckedTheDatasMayBeEmpty) {
  const TriMesh a = test::grid(4);
  CompareOptions o;
  o.direction = Direction::kForward;
  o.keep_samples = true;
  const ComparisonResult r = compare_meshes(a, a, o);
  ColoringOptions reversed;
  reversed.fixed_range = true;
  reversed.lo = 1.0;
  reversed.hi = 0.0;
  EXPECT_THROW(color_by_deviation(a, *r.forward, reversed), InvalidInput);
  const TriMesh colored = color_by_deviation(a, *r.forward, {});
  EXPECT_EQ(colored.channel("color")->values[1], map_color(0.0, 0.0, 0.0).y);
}

TEST(ColoredMesh, FaceSamplesAloneStillGiveEveryVertexAValue) {
  TriMesh a = test::grid(4);
  TriMesh b = test::grid(2, 1.0, 0.3);
  CompareOptions o;
  o.direction = Direction::kForward;
  o.sampling.vertices = false;
  o.keep_samples = true;
  ComparisonResult r = compare_meshes(a, b, o);
  const std::vector<double> v = vertex_deviation(a, *r.forward, 0);
  for (double x : v) EXPECT_NEAR(x, 0.3, 1e-12);
}

TEST(ColoredMesh, RequiresKeptSamples) {
  TriMesh a = test::grid(2);
  CompareOptions o;
  o.direction = Direction::kForward;
  ComparisonResult r = compare_meshes(a, a, o);
  EXPECT_THROW(color_by_deviation(a, *r.forward, {}), InvalidInput);
}

}  // namespace
}  // namespace meshdev
