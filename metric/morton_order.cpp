#include "metric/morton_order.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

namespace meshdev {
namespace {

constexpr std::uint32_t kMaxCell = (1u << 21) - 1;

// The 7 bits of x spread to every third bit (bit k -> bit 3k), for x in [0, 128).
struct SpreadTable {
  std::uint64_t bits[128];
  SpreadTable() {
    for (std::uint64_t x = 0; x < 128; ++x) {
      bits[x] = 0;
      for (int k = 0; k < 7; ++k) bits[x] |= (x >> k & 1u) << (3 * k);
    }
  }
};
const SpreadTable kSpread;

// The 21 bits of x spread to every third bit.
std::uint64_t spread21(std::uint32_t x) {
  return kSpread.bits[x & 127u] | kSpread.bits[x >> 7 & 127u] << 21 |
         kSpread.bits[x >> 14 & 127u] << 42;
}

}  // namespace

void morton_order(const Vec3* points, std::size_t n, const BoundingBox& box,
                  std::vector<std::uint32_t>& order, std::vector<std::uint64_t>& keys) {
  assert(n < (std::size_t{1} << 32));
  order.resize(n);
  std::iota(order.begin(), order.end(), 0u);
  if (n < 3 || box.empty()) return;
  const Vec3 extent = box.max - box.min;
  const double scale = kMaxCell / std::max({extent.x, extent.y, extent.z});
  if (!(scale > 0.0) || !std::isfinite(scale)) return;     // one point, or not finite
  auto cell = [&](double x, double x0) -> std::uint32_t {  // in [0, kMaxCell]; NaN: 0
    const double t = (x - x0) * scale;
    return t >= 0.0 ? (t < kMaxCell ? static_cast<std::uint32_t>(t) : kMaxCell) : 0u;
  };
  keys.resize(2 * n);  // the codes, then the radix sort's second buffer
  std::uint64_t least = ~std::uint64_t{0}, most = 0;
  std::size_t descents = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = points[i];
    const std::uint64_t code = spread21(cell(p.x, box.min.x)) |
                               spread21(cell(p.y, box.min.y)) << 1 |
                               spread21(cell(p.z, box.min.z)) << 2;
    keys[i] = code;
    descents += i > 0 && code < keys[i - 1];
    least = std::min(least, code);
    most = std::max(most, code);
  }
  if (descents == 0) return;
  // Every code shares the bits above the highest one in which the least and the most differ;
  // sort by the 30 bits from that one down, with the point's index in the low word.
  const int top = 63 - __builtin_clzll(least ^ most);  // least != most: there is a descent
  const int low = std::max(0, top - 29);
  for (std::size_t i = 0; i < n; ++i) keys[i] = (keys[i] >> low & 0x3fffffffu) << 32 | i;
  // LSD radix sort on those 30 bits, 8 per pass (stable: equal keys keep their order).
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
