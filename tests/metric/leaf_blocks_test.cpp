#include "metric/leaf_blocks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "metric/mesh.h"
#include "metric/plane_bounds.h"

namespace meshdev {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// A soup of triangles of every kind the margins tell apart: ordinary ones at several scales,
// slivers past kMaxCullKappa, triangles with a repeated corner (|ab x ac| = 0) and ones too small
// for kMinCullNormal2; corners shared between faces.
struct Soup {
  std::vector<double> positions;       // 3 per vertex
  std::vector<std::uint32_t> corners;  // 3 per face
};

Soup make_soup(std::mt19937_64& rng, std::size_t faces) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Soup s;
  auto add_vertex = [&](double x, double y, double z) {
    s.positions.insert(s.positions.end(), {x, y, z});
    return static_cast<std::uint32_t>(s.positions.size() / 3 - 1);
  };
  for (std::size_t f = 0; f < faces; ++f) {
    const double scale = std::pow(10.0, static_cast<int>(rng() % 9) - 6);  // 1e-6 .. 1e2
    const double cx = 50 * unit(rng), cy = 50 * unit(rng), cz = 50 * unit(rng);
    std::uint32_t v[3];
    for (auto& id : v)
      id = add_vertex(cx + scale * unit(rng), cy + scale * unit(rng), cz + scale * unit(rng));
    switch (f % 5) {
      case 1:  // a sliver: the third corner nearly on the line of the first two
        s.positions[3 * v[2] + 0] = 0.5 * (s.positions[3 * v[0]] + s.positions[3 * v[1]]);
        s.positions[3 * v[2] + 1] = 0.5 * (s.positions[3 * v[0] + 1] + s.positions[3 * v[1] + 1]);
        s.positions[3 * v[2] + 2] =
            0.5 * (s.positions[3 * v[0] + 2] + s.positions[3 * v[1] + 2]) + 1e-9 * scale;
        break;
      case 2:  // a repeated corner
        v[2] = v[0];
        break;
      case 3:  // a corner of an earlier face
        if (f > 0) v[1] = s.corners[3 * (f - 1)];
        break;
      default:
        break;
    }
    s.corners.insert(s.corners.end(), {v[0], v[1], v[2]});
  }
  return s;
}

// Both versions give the same block, bit for bit, and the same sums, for every count of faces.
TEST(LeafBlocks, BothVersionsGiveTheSameBlocksBitForBit) {
  if (simd_level() == SimdLevel::kBaseline) GTEST_SKIP() << "this CPU runs no AVX2";
  std::mt19937_64 rng(7);
  const Soup soup = make_soup(rng, 4000);
  const auto faces = static_cast<std::uint32_t>(soup.corners.size() / 3);
  const detail::FrameMap frames[] = {
      {{0.0, 0.0, 0.0}, 1.0}, {{1.5, -2.0, 30.0}, 1.0 / 70.0}, {{-3.0, 0.25, 7.0}, 1e3}};
  int margins_finite = 0, margins_infinite = 0;
  for (const detail::FrameMap& frame : frames)
    for (std::uint32_t round = 0; round < 3000; ++round) {
      const std::uint32_t count = 1 + round % 4;
      std::uint32_t ids[4];
      for (std::uint32_t lane = 0; lane < count; ++lane)
        ids[lane] = static_cast<std::uint32_t>(rng() % faces);
      detail::LeafBlock slow, fast;
      std::memset(&slow, 0xab, sizeof slow);
      std::memset(&fast, 0xcd, sizeof fast);
      const detail::LeafBlockSums a = detail::fill_leaf_block(
          soup.positions.data(), soup.corners.data(), ids, count, frame, slow);
      const detail::LeafBlockSums b = detail::fill_leaf_block_avx2(
          soup.positions.data(), soup.corners.data(), ids, count, frame, fast);
      ASSERT_EQ(std::memcmp(&slow, &fast, sizeof slow), 0)
          << "round " << round << ", count " << count;
      ASSERT_EQ(std::memcmp(&a.edge_sum, &b.edge_sum, sizeof(double)), 0) << "round " << round;
      ASSERT_EQ(std::memcmp(&a.corner_error2, &b.corner_error2, sizeof(double)), 0)
          << "round " << round;
      for (std::uint32_t lane = 0; lane < count; ++lane)
        ++(slow.margin[lane] == kInf ? margins_infinite : margins_finite);
    }
  // Both kinds of lane were compared.
  EXPECT_GT(margins_finite, 1000);
  EXPECT_GT(margins_infinite, 1000);
}

// The baseline against the definition, face by face: the corners are the frame coordinates
// rounded to float; empty lanes hold corners 0, margin +inf and kNoFace; the margin bounds
// 2^-18 (2 + kappa) from above within one float step (computed here in long double) or is +inf
// exactly for the degenerate faces; the sums are the longest edges and the largest corner error.
TEST(LeafBlocks, BaselineMatchesItsDefinition) {
  std::mt19937_64 rng(11);
  const Soup soup = make_soup(rng, 400);
  const detail::FrameMap frame{{2.0, -1.0, 0.5}, 1.0 / 60.0};
  for (std::uint32_t first = 0; first + 4 <= 400; first += 4) {
    const std::uint32_t count = 1 + first / 4 % 4;
    const std::uint32_t ids[4] = {first, first + 1, first + 2, first + 3};
    detail::LeafBlock block;
    const detail::LeafBlockSums sums = detail::fill_leaf_block(
        soup.positions.data(), soup.corners.data(), ids, count, frame, block);
    double edge_sum = 0, error2 = 0;
    for (std::uint32_t lane = 0; lane < 4; ++lane) {
      if (lane >= count) {
        EXPECT_EQ(block.face[lane], kNoFace);
        EXPECT_EQ(block.margin[lane], kInf);
        for (int c = 0; c < 3; ++c)
          for (int k = 0; k < 3; ++k) EXPECT_EQ(block.corner[c][k][lane], 0.0f);
        continue;
      }
      EXPECT_EQ(block.face[lane], ids[lane]);
      long double p[3][3];  // the rounded corners
      for (int c = 0; c < 3; ++c) {
        const double* x = &soup.positions[3 * soup.corners[3 * ids[lane] + c]];
        double e2 = 0;
        for (int k = 0; k < 3; ++k) {
          const double frame_x = (x[k] - frame.origin[k]) * frame.scale;
          EXPECT_EQ(block.corner[c][k][lane], static_cast<float>(frame_x));
          p[c][k] = block.corner[c][k][lane];
          e2 += (static_cast<double>(block.corner[c][k][lane]) - frame_x) *
                (static_cast<double>(block.corner[c][k][lane]) - frame_x);
        }
        error2 = std::max(error2, e2);
      }
      long double ab[3], ac[3], bc[3];
      for (int k = 0; k < 3; ++k) {
        ab[k] = p[1][k] - p[0][k];
        ac[k] = p[2][k] - p[0][k];
        bc[k] = p[2][k] - p[1][k];
      }
      auto sq = [](const long double v[3]) { return v[0] * v[0] + v[1] * v[1] + v[2] * v[2]; };
      edge_sum += static_cast<double>(std::sqrt(std::max({sq(ab), sq(ac), sq(bc)})));
      const long double n[3] = {ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2],
                                ab[0] * ac[1] - ab[1] * ac[0]};
      const long double kappa = std::sqrt(sq(ab) * sq(ac) / sq(n));
      if (sq(n) < 0.5L * kMinCullNormal2 || kappa > 2 * kMaxCullKappa || !std::isfinite(kappa)) {
        EXPECT_EQ(block.margin[lane], kInf) << "face " << ids[lane];
      } else if (sq(n) > 2 * kMinCullNormal2 && kappa < 0.5L * kMaxCullKappa) {
        const long double want = 0x1p-18L * (2 + kappa);
        EXPECT_GE(block.margin[lane], want * (1 - 1e-12L)) << "face " << ids[lane];
        EXPECT_LE(block.margin[lane], want * (1 + 0x1p-22L)) << "face " << ids[lane];
      }
    }
    EXPECT_NEAR(sums.edge_sum, edge_sum, 1e-12 * edge_sum);
    EXPECT_EQ(sums.corner_error2, error2);
  }
}

}  // namespace
}  // namespace meshdev
