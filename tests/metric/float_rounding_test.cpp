#include "metric/float_rounding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

namespace meshdev {
namespace {

constexpr float kMax = std::numeric_limits<float>::max();
constexpr float kInf = std::numeric_limits<float>::infinity();

// The twins: float(x), then std::nextafter where it went the wrong way, with the same ends.
float twin_down(double x) {
  if (x > kMax) return kMax;
  const float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -kInf) : f;
}
float twin_up(double x) {
  if (!(x <= kMax)) return kInf;  // NaN too
  if (x < -kMax) return -kMax;
  const float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, kInf) : f;
}

bool same_bits(float a, float b) {
  std::uint32_t x, y;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x == y || (a != a && b != b);
}

void expect_twins(double x) {
  EXPECT_TRUE(same_bits(round_down_to_float(x), twin_down(x)))
      << std::hexfloat << x << ": " << round_down_to_float(x) << " vs " << twin_down(x);
  EXPECT_TRUE(same_bits(round_up_to_float(x), twin_up(x)))
      << std::hexfloat << x << ": " << round_up_to_float(x) << " vs " << twin_up(x);
}

TEST(FloatRounding, EqualsTheNextafterTwinAtTheEnds) {
  const double specials[] = {0.0,
                             -0.0,
                             0x1p-149,
                             0x1p-150,
                             0x1.8p-150,
                             1e-300,
                             0x1p-126,
                             1.0,
                             0.1,
                             3.0,
                             1e30,
                             kMax,
                             0x1.ffffffp127,
                             1e39,
                             1e300,
                             std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::quiet_NaN()};
  for (double s : specials)
    for (double x : {s, -s})
      for (double y : {x, std::nextafter(x, 1e308), std::nextafter(x, -1e308)}) expect_twins(y);
  EXPECT_EQ(round_down_to_float(0.1), std::nextafter(0.1f, 0.0f));  // 0.1f is above 0.1
  EXPECT_EQ(round_up_to_float(0.1), 0.1f);
  EXPECT_EQ(round_down_to_float(-0.1), -0.1f);
  EXPECT_EQ(round_up_to_float(-0.1), std::nextafter(-0.1f, 0.0f));
}

TEST(FloatRounding, EqualsTheNextafterTwinOnRandomDoubles) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-2.0, 2.0);
  for (int i = 0; i < 200000; ++i) {
    const std::uint64_t bits = rng();
    double any;
    std::memcpy(&any, &bits, sizeof any);
    expect_twins(any);                          // any double: mostly far outside the float range
    expect_twins(unit(rng));                    // the frame's range
    expect_twins(std::ldexp(unit(rng), -140));  // float subnormals
    const auto fbits = static_cast<std::uint32_t>(rng());
    float f;
    std::memcpy(&f, &fbits, sizeof f);
    expect_twins(static_cast<double>(f));  // exact floats: no rounding
    if (::testing::Test::HasFailure()) return;
  }
}

}  // namespace
}  // namespace meshdev
