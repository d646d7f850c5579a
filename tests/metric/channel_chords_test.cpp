#include "metric/channel_chords.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "metric/attributes.h"
#include "metric/plane_bounds.h"

namespace meshdev {
namespace {

// channel_chords_x4 against its one-sample twin (barycentric_mix, unit_normal, norm, the raw
// Euclidean distance), bit for bit, on random values with zero, tiny and huge normals and on
// every dimension it takes; a channel of 4 raw components is left to the caller.
TEST(ChannelChords, FourLanesEqualTheOneSampleComputationBitForBit) {
  if (simd_level() == SimdLevel::kBaseline)
    GTEST_SKIP() << "the CPU (or MESHDEV_SIMD=baseline) has no AVX2: the kernel is never entered";
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  constexpr std::uint32_t kVertices = 64;
  std::vector<double> ref[5], tgt[5];  // [dim], 4: the 4-component channel
  for (int dim = 1; dim <= 4; ++dim) {
    ref[dim].resize(kVertices * dim);
    tgt[dim].resize(kVertices * dim);
    for (std::uint32_t v = 0; v < kVertices; ++v)
      for (int k = 0; k < dim; ++k) {
        const double scale = v % 11 == 0 ? 0.0 : v % 13 == 0 ? 1e-160 : v % 17 == 0 ? 1e150 : 1.0;
        ref[dim][v * dim + k] = scale * u(rng);
        tgt[dim][v * dim + k] = (v % 5 == 0 ? 0.0 : scale) * u(rng);
      }
  }
  const std::vector<detail::ChordChannel> channels = {{ref[3].data(), tgt[3].data(), 3, true},
                                                      {ref[1].data(), tgt[1].data(), 1, false},
                                                      {ref[2].data(), tgt[2].data(), 2, false},
                                                      {ref[3].data(), tgt[3].data(), 3, false},
                                                      {ref[4].data(), tgt[4].data(), 4, false}};
  std::uniform_int_distribution<std::uint32_t> vertex(0, kVertices - 1);
  std::size_t zero_normals = 0;
  for (int round = 0; round < 2000; ++round) {
    Triangle ta[4], tb[4];
    std::array<double, 3> ba[4], bb[4];
    detail::ChordSample s[4];
    for (int l = 0; l < 4; ++l) {
      for (int c = 0; c < 3; ++c) {
        ta[l][c] = vertex(rng);
        tb[l][c] = vertex(rng);
      }
      const double x = std::fabs(u(rng)), y = std::fabs(u(rng)) * (1 - x);
      ba[l] = {x, y, 1 - x - y};
      bb[l] = {y, 1 - x - y, x};
      s[l] = {ta[l].data(), ba[l].data(), tb[l].data(), bb[l].data()};
    }
    detail::ChannelChords out[5];
    out[4].chord[0] = -1.0;  // the 4-component channel: untouched
    detail::channel_chords_x4(channels.data(), channels.size(), s, out);
    EXPECT_EQ(out[4].chord[0], -1.0);
    for (int l = 0; l < 4; ++l) {
      auto value = [&](const std::vector<double>& v, int dim, const Triangle& t,
                       const std::array<double, 3>& bary, int k) {
        const std::size_t d = static_cast<std::size_t>(dim);
        return barycentric_mix(bary, v.data() + t[0] * d, v.data() + t[1] * d, v.data() + t[2] * d,
                               k);
      };
      const Vec3 na =
          unit_normal({value(ref[3], 3, ta[l], ba[l], 0), value(ref[3], 3, ta[l], ba[l], 1),
                       value(ref[3], 3, ta[l], ba[l], 2)});
      const Vec3 nb =
          unit_normal({value(tgt[3], 3, tb[l], bb[l], 0), value(tgt[3], 3, tb[l], bb[l], 1),
                       value(tgt[3], 3, tb[l], bb[l], 2)});
      const bool either_zero = na == Vec3{} || nb == Vec3{};
      zero_normals += either_zero;
      ASSERT_EQ(out[0].chord[l], norm(na - nb)) << "round " << round << ", lane " << l;
      ASSERT_EQ(out[0].across[l], norm(na + nb)) << "round " << round << ", lane " << l;
      ASSERT_EQ((out[0].either_zero >> l & 1) != 0, either_zero);
      for (int j = 1; j <= 3; ++j) {
        const int dim = channels[j].dim;
        double sum = 0.0;
        for (int k = 0; k < dim; ++k) {
          const double e =
              value(ref[dim], dim, ta[l], ba[l], k) - value(tgt[dim], dim, tb[l], bb[l], k);
          sum += e * e;
        }
        ASSERT_EQ(out[j].chord[l], std::sqrt(sum)) << "dim " << dim << ", round " << round;
      }
    }
  }
  EXPECT_GT(zero_normals, 100u);  // both sides of unit_normal's test
}

}  // namespace
}  // namespace meshdev
