#pragma once
// Directed rounding of doubles to float, for boxes and bounds that must stay conservative when
// stored in float (the BVH's node boxes, its leaf margins and search limits).

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

namespace meshdev {

// The largest float not above x; +max float for x = +inf (and above it), -inf below -max float,
// NaN for NaN. Exact; no branch on the data: float(x) (to nearest), then one step of its bits
// toward -inf where that went above x. The oracle is the test's twin on std::nextafter
// (tests/metric/float_rounding_test.cpp).
inline float round_down_to_float(double x) {
  const float f = static_cast<float>(x);
  std::int32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  const std::int32_t above = -static_cast<std::int32_t>(static_cast<double>(f) > x);
  bits += (-1 - 2 * (bits >> 31)) & above;  // f > 0: a step down in magnitude; f < 0: up
  float r;
  std::memcpy(&r, &bits, sizeof r);
  return std::min(r, std::numeric_limits<float>::max());  // (r = +inf only for x = +inf)
}

// The least float not below x; -max float for x = -inf (and below it), +inf above max float and
// for NaN (a bound that never culls). Exact, as round_down_to_float.
inline float round_up_to_float(double x) {
  if (x != x) return std::numeric_limits<float>::infinity();
  const float f = static_cast<float>(x);
  std::int32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  const std::int32_t below = -static_cast<std::int32_t>(static_cast<double>(f) < x);
  bits += (1 + 2 * (bits >> 31)) & below;  // f >= 0: a step up in magnitude; f < 0: down
  float r;
  std::memcpy(&r, &bits, sizeof r);
  return std::max(r, -std::numeric_limits<float>::max());  // (r = -inf only for x = -inf)
}

}  // namespace meshdev
