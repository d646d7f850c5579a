#include "metric/colormap.h"

#include <gtest/gtest.h>

#include <cmath>

#include "metric/errors.h"

namespace meshdev {
namespace {

// The paper's Fig. 4: blue at the minimum, green in the middle, red at the maximum.
TEST(Colormap, PaperScaleEndpointsAndMiddle) {
  EXPECT_EQ(map_color(2.0, 2.0, 4.0), (Vec3{0, 0, 1}));
  EXPECT_EQ(map_color(3.0, 2.0, 4.0), (Vec3{0, 1, 0}));
  EXPECT_EQ(map_color(4.0, 2.0, 4.0), (Vec3{1, 0, 0}));
  EXPECT_EQ(map_color(-9.0, 2.0, 4.0), (Vec3{0, 0, 1}));  // clamped below
  EXPECT_EQ(map_color(9.0, 2.0, 4.0), (Vec3{1, 0, 0}));   // clamped above
}

TEST(Colormap, EmptyRangeAndNaNGiveTheMiddleColour) {
  EXPECT_EQ(map_color(1.0, 1.0, 1.0), (Vec3{0, 1, 0}));
  EXPECT_EQ(map_color(std::nan(""), 0.0, 1.0), (Vec3{0, 1, 0}));
}

// A range a user gives must be finite and increasing: NaN or reversed ends gave a mesh of one
// colour without a word.
TEST(Colormap, AUserRangeMustBeFiniteAndIncreasing) {
  EXPECT_NO_THROW(check_color_range(0.0, 1e-9));
  EXPECT_NO_THROW(check_color_range(-2.0, -1.0));
  EXPECT_THROW(check_color_range(1.0, 0.0), InvalidInput);
  EXPECT_THROW(check_color_range(1.0, 1.0), InvalidInput);
  EXPECT_THROW(check_color_range(std::nan(""), 1.0), InvalidInput);
  EXPECT_THROW(check_color_range(0.0, INFINITY), InvalidInput);
}

TEST(Colormap, PerceptualScalesAreMonotoneInLightnessAtTheEnds) {
  const Vec3 lo = map_color(0, 0, 1, ColorScale::kViridis),
             hi = map_color(1, 0, 1, ColorScale::kViridis);
  EXPECT_LT(lo.x + lo.y + lo.z, hi.x + hi.y + hi.z);
  EXPECT_THROW(parse_color_scale("rainbow"), InvalidInput);
  EXPECT_EQ(parse_color_scale("turbo"), ColorScale::kTurbo);
}

}  // namespace
}  // namespace meshdev
