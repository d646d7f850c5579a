// The software rasteriser and the colour bar: colours land where the geometry is, nearer wins.
#include "metric/render.h"

#include <gtest/gtest.h>

#include <cmath>

#include "metric/colorbar.h"
#include "metric/errors.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

TriMesh colored(TriMesh m, const Vec3& c) {
  AttributeChannel& color = m.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    color.values[3 * v] = c.x;
    color.values[3 * v + 1] = c.y;
    color.values[3 * v + 2] = c.z;
  }
  return m;
}

RenderOptions front_unlit() {
  RenderOptions o;
  o.views = {View::kFront};
  o.size = 64;
  o.ambient = 1.0;  // unlit: the pixel is the colour
  o.labels = false;
  return o;
}

TEST(Render, VertexColoursShowWhereTheMeshIs) {
  const Image img = render_mesh(colored(test::square(), {1, 0, 0}), nullptr, front_unlit());
  ASSERT_EQ(img.width, 64);
  EXPECT_EQ(img.pixel(32, 32), (Vec3{1, 0, 0}));  // the square covers the centre
  EXPECT_EQ(img.pixel(1, 1), (Vec3{1, 1, 1}));    // the corner is background
}

// Options out of range are refused by name; a NaN ambient light passed the command line's
// [0, 1] check and drew pixels from lround(NaN). A NaN colour is drawn as 0.
TEST(Render, OptionsOutOfRangeAreRefusedAndNaNColoursAreBlack) {
  const TriMesh m = colored(test::square(), {1, 0, 0});
  for (double ambient : {std::nan(""), -0.1, 1.5}) {
    RenderOptions o = front_unlit();
    o.ambient = ambient;
    EXPECT_THROW(render_mesh(m, nullptr, o), InvalidInput) << ambient;
  }
  RenderOptions o = front_unlit();
  o.size = 8;
  EXPECT_THROW(render_mesh(m, nullptr, o), InvalidInput);
  Image img(2, 1);
  img.set(0, 0, {std::nan(""), 0.5, 2.0});
  EXPECT_EQ(img.rgb[0], 0);
  EXPECT_EQ(img.rgb[1], 128);
  EXPECT_EQ(img.rgb[2], 255);
}

TEST(Render, TheNearerSurfaceWinsTheDepthTest) {
  // A red square at z = 0 and a smaller blue one at z = 0.5 in front of it (front view looks
  // down -z): the centre is blue, a point of the red square outside the blue one is red.
  TriMesh red = colored(test::square(), {1, 0, 0});
  TriMesh blue = colored(test::translated(test::square(0.5), {0.25, 0.25, 0.5}), {0, 0, 1});
  const auto offset = static_cast<std::uint32_t>(red.positions.size());
  red.positions.insert(red.positions.end(), blue.positions.begin(), blue.positions.end());
  for (Triangle t : blue.faces) red.faces.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  AttributeChannel& c = *red.channel("color");
  const std::vector<double> more = blue.channel("color")->values;
  c.values.insert(c.values.end(), more.begin(), more.end());
  // Draw the far square last too: order must not matter.
  std::reverse(red.faces.begin(), red.faces.end());
  const Image img = render_mesh(red, nullptr, front_unlit());
  EXPECT_EQ(img.pixel(32, 32), (Vec3{0, 0, 1}));
  // 39 pixels per unit: the red square spans pixels ~12-52, the blue one ~22-42.
  EXPECT_EQ(img.pixel(32, 26), (Vec3{0, 0, 1}));
  EXPECT_EQ(img.pixel(16, 32), (Vec3{1, 0, 0}));  // in the red square, left of the blue one
}

TEST(Render, TextureIsLookedUpAtTheInterpolatedUv) {
  TriMesh m = test::square();
  AttributeChannel& uv =
      m.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerVertex, 2);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    uv.values[2 * v] = m.positions[v].x;
    uv.values[2 * v + 1] = m.positions[v].y;
  }
  Image tex(2, 1, {0, 1, 0});
  tex.set(1, 0, {1, 0, 1});  // right half magenta
  RenderOptions o = front_unlit();
  const Image img = render_mesh(m, &tex, o);
  // 41.6 pixels per unit, centred: u = 0.25 (left texel centre) at x ≈ 21.6, u = 0.75 at ≈ 42.4.
  auto near = [](const Vec3& a, const Vec3& b) { return norm(a - b) < 0.03; };
  EXPECT_TRUE(near(img.pixel(21, 32), {0, 1, 0}));
  EXPECT_TRUE(near(img.pixel(42, 32), {1, 0, 1}));
  EXPECT_THROW(parse_views("front,sideways"), InvalidInput);
  EXPECT_EQ(parse_views("all").size(), 7u);
}

TEST(ColorBar, ShowsTheScaleEndsAndMiddleWithNumbers) {
  ColorBarOptions o;
  o.lo = 0;
  o.hi = 2;
  o.title = "geometry";
  const Image img = colorbar_image(o);
  // Find the bar's row: the first row whose left end (inside the frame) is saturated blue.
  auto near = [](const Vec3& a, const Vec3& b) { return norm(a - b) < 0.03; };
  int row = -1;
  for (int y = 0; y < img.height && row < 0; ++y)
    if (near(img.pixel(24, y), {0, 0, 1})) row = y + 5;
  ASSERT_GE(row, 0);
  EXPECT_TRUE(near(img.pixel(24, row), {0, 0, 1}));              // minimum: blue
  EXPECT_TRUE(near(img.pixel(img.width / 2, row), {0, 1, 0}));   // middle: green
  EXPECT_TRUE(near(img.pixel(img.width - 25, row), {1, 0, 0}));  // maximum: red
  const std::string svg = colorbar_svg(o);
  for (const char* label : {">0<", ">0.5<", ">1<", ">1.5<", ">2<", "geometry"})
    EXPECT_NE(svg.find(label), std::string::npos) << label;
}

}  // namespace
}  // namespace meshdev
