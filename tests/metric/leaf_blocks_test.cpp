#include "metric/leaf_blocks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <sys/mman.h>
#include <unistd.h>

#include "metric/mesh.h"
#include "metric/plane_bounds.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Both versions give the same block, bit for bit, and the same sums, for every count of faces.
TEST(LeafBlocks, BothVersionsGiveTheSameBlocksBitForBit) {
  if (simd_level() == SimdLevel::kBaseline) GTEST_SKIP() << "this CPU runs no AVX2";
  // Ordinary triangles at several scales, slivers past kMaxCullKappa, repeated corners (|ab x ac| =
  // 0), corners shared between faces: every kind the margins tell apart.
  const TriMesh soup = test::kernel_soup(4000, 7);
  const double* positions = &soup.positions[0].x;
  const std::uint32_t* corners = soup.faces[0].data();
  const auto faces = static_cast<std::uint32_t>(soup.faces.size());
  std::mt19937_64 rng(7);
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
      const detail::LeafBlockSums a =
          detail::fill_leaf_block(positions, corners, ids, count, frame, slow);
      const detail::LeafBlockSums b =
          detail::fill_leaf_block_avx2(positions, corners, ids, count, frame, fast);
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

// The AVX2 version reads each corner's three coordinates and nothing after them: a mesh whose last
// vertex ends where an unreadable page begins gives the same block as the baseline, no fault.
TEST(LeafBlocks, AvxVersionReadsNothingPastTheLastVertex) {
  if (simd_level() == SimdLevel::kBaseline) GTEST_SKIP() << "this CPU runs no AVX2";
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  void* map = mmap(nullptr, 2 * page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(map, MAP_FAILED);
  auto* bytes = static_cast<unsigned char*>(map);
  ASSERT_EQ(mprotect(bytes + page, page, PROT_NONE), 0);
  constexpr std::size_t kVertices = 4;
  auto* positions = reinterpret_cast<double*>(bytes + page) - 3 * kVertices;
  const double corners_xyz[3 * kVertices] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.25, 0.5, 2};
  std::memcpy(positions, corners_xyz, sizeof corners_xyz);
  const std::uint32_t corners[] = {0, 1, 3, 3, 2, 1, 1, 3, 0, 2, 0, 3};
  const std::uint32_t ids[] = {0, 1, 2, 3};
  const detail::FrameMap frame{{0.5, 0.5, 1.0}, 0.5};
  for (std::uint32_t count = 1; count <= 4; ++count) {
    detail::LeafBlock slow, fast;
    std::memset(&slow, 0xab, sizeof slow);
    std::memset(&fast, 0xcd, sizeof fast);
    detail::fill_leaf_block(positions, corners, ids, count, frame, slow);
    detail::fill_leaf_block_avx2(positions, corners, ids, count, frame, fast);
    EXPECT_EQ(std::memcmp(&slow, &fast, sizeof slow), 0) << "count " << count;
  }
  munmap(map, 2 * page);
}

// The baseline against the definition, face by face: the corners are the frame coordinates
// rounded to float; empty lanes hold corners 0, margin +inf and kNoFace; the margin bounds
// 2^-18 (2 + kappa) from above within one float step (computed here in long double) or is +inf
// exactly for the degenerate faces; the sums are the longest edges and the largest corner error.
TEST(LeafBlocks, BaselineMatchesItsDefinition) {
  const TriMesh soup = test::kernel_soup(400, 11);
  const detail::FrameMap frame{{2.0, -1.0, 0.5}, 1.0 / 60.0};
  for (std::uint32_t first = 0; first + 4 <= 400; first += 4) {
    const std::uint32_t count = 1 + first / 4 % 4;
    const std::uint32_t ids[4] = {first, first + 1, first + 2, first + 3};
    detail::LeafBlock block;
    const detail::LeafBlockSums sums = detail::fill_leaf_block(
        &soup.positions[0].x, soup.faces[0].data(), ids, count, frame, block);
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
        const double* x = &soup.positions[soup.faces[ids[lane]][c]].x;
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
