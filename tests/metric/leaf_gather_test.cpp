#include "metric/leaf_gather.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "metric/plane_bounds.h"

namespace meshdev {
namespace {

using detail::GatheredBlocks;
using detail::kWideEmpty;
using detail::kWideLeafBit;
using detail::WideNode;

// A random 4-wide tree: nodes[0] the root; each node has 1 to 4 children (an empty lane
// anywhere), inner ones down to `depth` levels, leaves numbered in creation order.
struct RandomTree {
  std::vector<WideNode> nodes;
  std::uint32_t leaves = 0;

  RandomTree(std::mt19937_64& rng, int depth) { make(rng, depth, -1.0f, 1.0f); }

  std::uint32_t make(std::mt19937_64& rng, int depth, float lo, float hi) {
    const auto id = static_cast<std::uint32_t>(nodes.size());
    nodes.emplace_back();
    std::uniform_real_distribution<float> u(lo, hi);
    std::uniform_int_distribution<int> lane(0, 3), kind(0, 9);
    const int hole = kind(rng) < 3 ? lane(rng) : -1;  // a child left empty
    for (int k = 0; k < 4; ++k) {
      float clo[3], chi[3];
      for (int a = 0; a < 3; ++a) {
        const float x = u(rng), y = u(rng);
        clo[a] = std::min(x, y);
        chi[a] = std::max(x, y);
      }
      std::uint32_t ref;
      if (k == hole) {
        ref = kWideEmpty;
        for (int a = 0; a < 3; ++a) {
          clo[a] = std::numeric_limits<float>::infinity();
          chi[a] = -std::numeric_limits<float>::infinity();
        }
      } else if (depth > 1 && kind(rng) < 6) {
        ref = make(rng, depth - 1, std::min(clo[0], clo[1]), std::max(chi[0], chi[1]));
      } else {
        ref = kWideLeafBit | leaves++;
      }
      WideNode& node = nodes[id];  // after make(): emplace_back may have moved it
      node.child[k] = ref;
      for (int a = 0; a < 3; ++a) {
        node.lo[a][k] = clo[a];
        node.hi[a][k] = chi[a];
      }
    }
    return id;
  }
};

// The definition, one node at a time in plain floats: block b is gathered iff its box and every
// ancestor's lie within `limit2` of [lo, hi].
void brute_force(const RandomTree& tree, std::uint32_t node, const float lo[3], const float hi[3],
                 float limit2, std::vector<std::uint32_t>& out) {
  const WideNode& n = tree.nodes[node];
  for (int k = 0; k < 4; ++k) {
    if (n.child[k] == kWideEmpty) continue;
    float d2 = 0.0f;
    for (int a = 0; a < 3; ++a) {
      const float d = std::max(std::max(n.lo[a][k] - hi[a], lo[a] - n.hi[a][k]), 0.0f);
      d2 = d2 + d * d;
    }
    if (d2 > limit2) continue;
    if ((n.child[k] & kWideLeafBit) != 0)
      out.push_back(n.child[k] & ~kWideLeafBit);
    else
      brute_force(tree, n.child[k], lo, hi, limit2, out);
  }
}

struct Gathered {
  std::size_t count = 0;
  std::vector<std::uint32_t> block;
  std::vector<float> lo[3], hi[3];
};

template <class Gather>
Gathered run(Gather gather, const RandomTree& tree, const float lo[3], const float hi[3],
             float limit2, std::size_t max_blocks, std::size_t queue_size) {
  Gathered g;
  g.block.assign(max_blocks + 4, 0);
  for (int a = 0; a < 3; ++a) {
    g.lo[a].assign(max_blocks + 4, 0.0f);
    g.hi[a].assign(max_blocks + 4, 0.0f);
  }
  std::vector<std::uint32_t> queue(queue_size + 4);
  const GatheredBlocks out{g.block.data(),
                           {g.lo[0].data(), g.lo[1].data(), g.lo[2].data()},
                           {g.hi[0].data(), g.hi[1].data(), g.hi[2].data()}};
  g.count = gather(tree.nodes.data(), 0, lo, hi, limit2, max_blocks, queue.data(), queue_size, out);
  return g;
}

// On 300 random trees and query boxes of every size: the baseline gathers exactly the blocks of
// the definition, each with its box as its parent stores it, breadth first (a block's depth never
// below the one before it); the AVX version gives the same output, element for element.
TEST(LeafGather, EqualsTheDefinitionAndTheAvxVersionEqualsTheBaseline) {
  const bool avx = simd_level() != SimdLevel::kBaseline;
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<float> u(-1.2f, 1.2f), size(0.0f, 0.6f), reach(0.0f, 0.5f);
  std::size_t nonempty = 0;
  for (int round = 0; round < 300; ++round) {
    const RandomTree tree(rng, 2 + round % 5);
    // Each block's box and depth, from its parent.
    std::vector<float> box(6 * tree.leaves);
    std::vector<int> depth(tree.leaves);
    auto record = [&](auto&& self, std::uint32_t node, int level) -> void {
      const WideNode& n = tree.nodes[node];
      for (int k = 0; k < 4; ++k) {
        if (n.child[k] == kWideEmpty) continue;
        if ((n.child[k] & kWideLeafBit) == 0) {
          self(self, n.child[k], level + 1);
          continue;
        }
        const std::uint32_t b = n.child[k] & ~kWideLeafBit;
        depth[b] = level;
        for (int a = 0; a < 3; ++a) {
          box[6 * b + a] = n.lo[a][k];
          box[6 * b + 3 + a] = n.hi[a][k];
        }
      }
    };
    record(record, 0, 0);
    for (int query = 0; query < 20; ++query) {
      float lo[3], hi[3];
      for (int a = 0; a < 3; ++a) {
        lo[a] = u(rng);
        hi[a] = lo[a] + size(rng);
      }
      const float r = reach(rng);
      const float limit2 = query == 0 ? std::numeric_limits<float>::infinity() : r * r;
      std::vector<std::uint32_t> expected;
      brute_force(tree, 0, lo, hi, limit2, expected);
      const std::size_t max_blocks = tree.leaves;
      const Gathered base =
          run(detail::gather_leaf_blocks, tree, lo, hi, limit2, max_blocks, tree.nodes.size());
      ASSERT_EQ(base.count, expected.size());
      nonempty += base.count > 0;
      std::vector<std::uint32_t> got(base.block.begin(),
                                     base.block.begin() + static_cast<std::ptrdiff_t>(base.count));
      for (std::size_t i = 0; i < base.count; ++i) {
        const std::uint32_t b = got[i];
        ASSERT_LT(b, tree.leaves);
        if (i > 0) {
          EXPECT_GE(depth[b], depth[got[i - 1]]) << "not breadth first";
        }
        for (int a = 0; a < 3; ++a) {
          EXPECT_EQ(base.lo[a][i], box[6 * b + a]);
          EXPECT_EQ(base.hi[a][i], box[6 * b + 3 + a]);
        }
      }
      std::sort(got.begin(), got.end());
      std::sort(expected.begin(), expected.end());
      EXPECT_EQ(got, expected);
      if (!avx) continue;
      const Gathered fast =
          run(detail::gather_leaf_blocks_avx2, tree, lo, hi, limit2, max_blocks, tree.nodes.size());
      ASSERT_EQ(fast.count, base.count);
      for (std::size_t i = 0; i < base.count; ++i) {
        EXPECT_EQ(fast.block[i], base.block[i]);
        for (int a = 0; a < 3; ++a) {
          EXPECT_EQ(fast.lo[a][i], base.lo[a][i]);
          EXPECT_EQ(fast.hi[a][i], base.hi[a][i]);
        }
      }
    }
  }
  EXPECT_GT(nonempty, 1000u);  // the query boxes reach blocks most of the time
}

// More blocks within reach than max_blocks, or more nodes to open than the queue holds: both
// versions say so (a count above max_blocks) instead of writing past their arrays.
TEST(LeafGather, ReportsTooManyBlocksAndTooManyNodes) {
  std::mt19937_64 rng(43);
  const RandomTree tree(rng, 6);
  ASSERT_GT(tree.leaves, 8u);
  ASSERT_GT(tree.nodes.size(), 8u);
  const float lo[3] = {-2.0f, -2.0f, -2.0f}, hi[3] = {2.0f, 2.0f, 2.0f};
  const float all = std::numeric_limits<float>::infinity();
  std::vector<decltype(&detail::gather_leaf_blocks)> versions = {detail::gather_leaf_blocks};
  if (simd_level() != SimdLevel::kBaseline) versions.push_back(detail::gather_leaf_blocks_avx2);
  for (auto gather : versions) {
    EXPECT_EQ(run(gather, tree, lo, hi, all, tree.leaves, tree.nodes.size()).count, tree.leaves);
    EXPECT_GT(run(gather, tree, lo, hi, all, tree.leaves - 1, tree.nodes.size()).count,
              tree.leaves - 1);
    EXPECT_GT(run(gather, tree, lo, hi, all, 4, tree.nodes.size()).count, 4u);
    EXPECT_GT(run(gather, tree, lo, hi, all, tree.leaves, 4).count, tree.leaves);
  }
}

// A query's blocks among a packet's: the definition (box gap squared in float, kept unless above
// the limit) for every count up to 140, and the AVX version's list equal to the baseline's. Rows
// past the count hold boxes that would be kept (the query's own point), so a version that read
// them as blocks would fail; NaN coordinates give SSE's max (the walk's arithmetic).
TEST(LeafGather, BlocksNearPointEqualTheDefinitionInBothVersions) {
  const bool avx = simd_level() != SimdLevel::kBaseline;
  std::mt19937_64 rng(46);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), size(0.0f, 0.6f), reach(0.0f, 0.8f);
  std::size_t kept_total = 0, rows_total = 0;
  for (int round = 0; round < 600; ++round) {
    const std::size_t count = static_cast<std::size_t>(round) % 141;
    const std::size_t rows = (count + 7) / 8 * 8;
    const float q[3] = {u(rng), u(rng), u(rng)};
    alignas(16) float lo[3][144], hi[3][144];
    for (std::size_t b = 0; b < rows; ++b)
      for (int a = 0; a < 3; ++a) {
        lo[a][b] = b < count ? u(rng) : q[a];
        hi[a][b] = b < count ? lo[a][b] + size(rng) : q[a];
      }
    if (count > 3 && round % 5 == 0) lo[1][count / 2] = std::numeric_limits<float>::quiet_NaN();
    if (count > 3 && round % 5 == 1) hi[2][count / 3] = std::numeric_limits<float>::quiet_NaN();
    const float r = reach(rng);
    const float limit2 = r * r;
    // SSE's max: the second operand where either is NaN.
    auto max = [](float x, float y) { return x > y ? x : y; };
    std::vector<std::uint8_t> expected;
    for (std::size_t b = 0; b < count; ++b) {
      float gap2 = 0.0f;
      for (int a = 0; a < 3; ++a) {
        const float gap = max(max(lo[a][b] - q[a], q[a] - hi[a][b]), 0.0f);
        gap2 = gap2 + gap * gap;
      }
      if (!(gap2 > limit2)) expected.push_back(static_cast<std::uint8_t>(b));
    }
    const float* const l[3] = {lo[0], lo[1], lo[2]};
    const float* const h[3] = {hi[0], hi[1], hi[2]};
    std::uint8_t which[152];
    const std::size_t n = detail::blocks_near_point(l, h, count, q, limit2, which);
    SCOPED_TRACE(testing::Message() << "round " << round << ", " << count << " blocks");
    ASSERT_EQ(std::vector<std::uint8_t>(which, which + n), expected);
    kept_total += n;
    rows_total += count;
    if (!avx) continue;
    std::uint8_t fast[152];
    const std::size_t m = detail::blocks_near_point_avx2(l, h, count, q, limit2, fast);
    ASSERT_EQ(std::vector<std::uint8_t>(fast, fast + m), expected);
  }
  // Neither none nor all: the reach keeps some of the blocks.
  EXPECT_GT(kept_total, rows_total / 20);
  EXPECT_LT(kept_total, rows_total / 2);
}

}  // namespace
}  // namespace meshdev
