#include "metric/morton_order.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

namespace meshdev {
namespace {

// The 10 bits of x spread to every third bit (bit k -> bit 3k), for x in [0, 1024).
struct SpreadTable {
  std::uint32_t bits[1024];
  SpreadTable() {
    for (std::uint32_t x = 0; x < 1024; ++x) {
      bits[x] = 0;
      for (int k = 0; k < 10; ++k) bits[x] |= (x >> k & 1u) << (3 * k);
    }
  }
};
const SpreadTable kSpread;

}  // namespace

void morton_order(const Vec3* points, std::size_t n, std::vector<std::uint32_t>& order,
                  std::vector<std::uint64_t>& keys) {
  assert(n < (std::size_t{1} << 32));
  order.resize(n);
  std::iota(order.begin(), order.end(), 0u);
  if (n < 3) return;
  Vec3 lo = points[0], hi = points[0];
  for (std::size_t i = 1; i < n; ++i) {
    lo = {std::min(lo.x, points[i].x), std::min(lo.y, points[i].y), std::min(lo.z, points[i].z)};
    hi = {std::max(hi.x, points[i].x), std::max(hi.y, points[i].y), std::max(hi.z, points[i].z)};
  }
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  const double scale = 1023.0 / extent;
  if (!(extent > 0.0) || !std::isfinite(scale)) return;  // one point, or not finite
  keys.resize(2 * n);  // the keys, then the radix sort's second buffer
  std::size_t descents = 0;
  for (std::size_t i = 0; i < n; ++i) {
    auto cell = [&](double x, double x0) -> std::uint32_t {  // in [0, 1023]; NaN: 0
      const double t = (x - x0) * scale;
      return t >= 0.0 ? (t < 1023.0 ? static_cast<std::uint32_t>(t) : 1023u) : 0u;
    };
    const std::uint32_t code = kSpread.bits[cell(points[i].x, lo.x)] |
                               kSpread.bits[cell(points[i].y, lo.y)] << 1 |
                               kSpread.bits[cell(points[i].z, lo.z)] << 2;
    keys[i] = static_cast<std::uint64_t>(code) << 32 | i;
    descents += i > 0 && keys[i] < keys[i - 1];
  }
  if (descents == 0) return;
  // LSD radix sort on the 30 code bits, 8 per pass (stable: equal codes keep their order).
  std::uint64_t* from = keys.data();
  std::uint64_t* to = keys.data() + n;
  for (int shift = 32; shift < 62; shift += 8) {
    std::size_t start[257] = {};
    for (std::size_t i = 0; i < n; ++i) ++start[(from[i] >> shift & 0xffu) + 1];
    for (int b = 0; b < 256; ++b) start[b + 1] += start[b];
    for (std::size_t i = 0; i < n; ++i) to[start[from[i] >> shift & 0xffu]++] = from[i];
    std::swap(from, to);
  }
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(from[i]);
}

}  // namespace meshdev
