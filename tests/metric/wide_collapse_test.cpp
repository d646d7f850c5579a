#include "metric/wide_collapse.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace meshdev {
namespace {

// A binary tree: node 0 is the root; an inner node has two children, a leaf none.
struct BinaryTree {
  struct Node {
    double half_area = 0;
    int left = -1, right = -1;  // -1: a leaf
    bool leaf() const { return left < 0; }
  };
  std::vector<Node> nodes;
};

// A random tree of `leaves` leaves (split at a random point), its half areas random in (0, 1].
int grow(BinaryTree& t, int leaves, std::mt19937& rng) {
  const int id = static_cast<int>(t.nodes.size());
  t.nodes.emplace_back();
  t.nodes[id].half_area = std::uniform_real_distribution<double>(0.01, 1.0)(rng);
  if (leaves > 1) {
    const int left = std::uniform_int_distribution<int>(1, leaves - 1)(rng);
    const int l = grow(t, left, rng);
    const int r = grow(t, leaves - left, rng);
    t.nodes[id].left = l;
    t.nodes[id].right = r;
  }
  return id;
}

// A perfect tree of 2^levels leaves whose half areas halve at each level down from 1.
int grow_perfect(BinaryTree& t, int levels, double half_area = 1.0) {
  const int id = static_cast<int>(t.nodes.size());
  t.nodes.emplace_back();
  t.nodes[id].half_area = half_area;
  if (levels > 0) {
    const int l = grow_perfect(t, levels - 1, half_area / 2);
    const int r = grow_perfect(t, levels - 1, half_area / 2);
    t.nodes[id].left = l;
    t.nodes[id].right = r;
  }
  return id;
}

// The plans of every inner node, bottom up, as TriangleBvh::build makes them; the root's costs.
detail::CollapseCosts plan_tree(const BinaryTree& t, int node, std::vector<std::uint32_t>& plan) {
  const BinaryTree::Node& n = t.nodes[static_cast<std::size_t>(node)];
  if (n.leaf()) return {};
  const detail::CollapseCosts l = plan_tree(t, n.left, plan), r = plan_tree(t, n.right, plan);
  detail::CollapseCosts out;
  plan[static_cast<std::size_t>(node)] = detail::collapse_plan(n.half_area, l, r, out);
  return out;
}

// The collapse the plans give, walked with metric/wide_collapse.h's walks as TriangleBvh::build
// walks it: its cost (summed half areas of its wide nodes), its wide nodes' child counts and its
// leaves in order.
struct Collapse {
  double cost = 0;
  std::vector<int> child_counts;
  std::vector<int> leaves;
};
void walk(const BinaryTree& t, const std::vector<std::uint32_t>& plan, int node, Collapse& c) {
  const BinaryTree::Node& n = t.nodes[static_cast<std::size_t>(node)];
  if (n.leaf()) {
    c.leaves.push_back(node);
    return;
  }
  auto inner = [&](std::uint32_t id, std::uint32_t& left, std::uint32_t& right, std::uint32_t& p) {
    const BinaryTree::Node& x = t.nodes[id];
    if (x.leaf()) return false;
    left = static_cast<std::uint32_t>(x.left), right = static_cast<std::uint32_t>(x.right);
    p = plan[id];
    return true;
  };
  const std::uint32_t share = detail::plan_wide_share(plan[static_cast<std::size_t>(node)]);
  ASSERT_GE(share, 1u);
  ASSERT_LE(share, 3u);
  std::vector<int> kids;
  detail::for_each_wide_child(inner, static_cast<std::uint32_t>(node),
                              [&](std::uint32_t kid) { kids.push_back(static_cast<int>(kid)); });
  c.cost += n.half_area;
  c.child_counts.push_back(static_cast<int>(kids.size()));
  for (int kid : kids) walk(t, plan, kid, c);
}

// The brute-force twin: every set of at most 4 nodes that covers a subtree (the node itself, or
// covers of its two children joined), and the least cost of a wide node over all of them.
std::vector<std::vector<int>> covers(const BinaryTree& t, int node) {
  std::vector<std::vector<int>> out{{node}};
  const BinaryTree::Node& n = t.nodes[static_cast<std::size_t>(node)];
  if (n.leaf()) return out;
  for (const auto& a : covers(t, n.left))
    for (const auto& b : covers(t, n.right))
      if (a.size() + b.size() <= 4) {
        std::vector<int> both = a;
        both.insert(both.end(), b.begin(), b.end());
        out.push_back(both);
      }
  return out;
}
double least_wide_cost(const BinaryTree& t, int node) {
  const BinaryTree::Node& n = t.nodes[static_cast<std::size_t>(node)];
  double best = std::numeric_limits<double>::infinity();
  for (const auto& a : covers(t, n.left))
    for (const auto& b : covers(t, n.right)) {
      if (a.size() + b.size() > 4) continue;
      double cost = n.half_area;
      for (const auto* side : {&a, &b})
        for (int x : *side)
          if (!t.nodes[static_cast<std::size_t>(x)].leaf()) cost += least_wide_cost(t, x);
      best = std::min(best, cost);
    }
  return best;
}

std::vector<int> leaves_in_order(const BinaryTree& t, int node) {
  const BinaryTree::Node& n = t.nodes[static_cast<std::size_t>(node)];
  if (n.leaf()) return {node};
  std::vector<int> l = leaves_in_order(t, n.left), r = leaves_in_order(t, n.right);
  l.insert(l.end(), r.begin(), r.end());
  return l;
}

// On random trees of 2 to 14 leaves, the plans' collapse costs what the brute force finds least,
// which is also the root's forest[0]; every wide node has 2 to 4 children; the leaves keep their
// order.
TEST(WideCollapse, PlansGiveTheLeastCostOfTheBruteForce) {
  std::mt19937 rng(11);
  for (int round = 0; round < 400; ++round) {
    BinaryTree t;
    grow(t, 2 + round % 13, rng);
    std::vector<std::uint32_t> plan(t.nodes.size(), 0);
    const detail::CollapseCosts root = plan_tree(t, 0, plan);
    Collapse c;
    walk(t, plan, 0, c);
    const double brute = least_wide_cost(t, 0);
    ASSERT_NEAR(c.cost, brute, 1e-12 * brute) << "round " << round;
    ASSERT_NEAR(root.forest[0], brute, 1e-12 * brute) << "round " << round;
    for (int k : c.child_counts) {
      ASSERT_GE(k, 2) << "round " << round;
      ASSERT_LE(k, 4) << "round " << round;
    }
    ASSERT_EQ(c.leaves, leaves_in_order(t, 0)) << "round " << round;
    for (std::size_t i = 0; i < t.nodes.size(); ++i)
      ASSERT_TRUE(t.nodes[i].leaf() || (plan[i] & detail::kCollapsePlanned) != 0) << i;
  }
}

// Eight leaves under a perfect tree whose half areas halve level by level (1, 1/2, 1/4): opening
// the child of largest area until a node has four children costs 1 + 4 / 4 = 2 in five nodes,
// two nodes of four leaves 1 + 2 / 2 = 2 in three; the least is 1 + 1/2 + 1/4 = 1.75 in three
// (the root holds two leaves, a node of two and a node of four).
TEST(WideCollapse, EightLeavesTakeThreeNodes) {
  BinaryTree t;
  grow_perfect(t, 3);
  std::vector<std::uint32_t> plan(t.nodes.size(), 0);
  const detail::CollapseCosts root = plan_tree(t, 0, plan);
  Collapse c;
  walk(t, plan, 0, c);
  EXPECT_DOUBLE_EQ(c.cost, 1.75);
  EXPECT_DOUBLE_EQ(root.forest[0], 1.75);
  ASSERT_EQ(c.child_counts.size(), 3u);
  std::vector<int> counts = c.child_counts;
  std::sort(counts.begin(), counts.end());
  EXPECT_EQ(counts, (std::vector<int>{2, 4, 4}));
  // Covers by more roots: two, the children as wide nodes (1/2 + 1/2); three, one child opened
  // (1/4 + 1/4 + 1/2); four, a grandchild opened into its two leaves (1/4 + 1/2), which is the
  // root's children above.
  EXPECT_DOUBLE_EQ(root.forest[1], 1.0);
  EXPECT_DOUBLE_EQ(root.forest[2], 1.0);
  EXPECT_DOUBLE_EQ(root.forest[3], 0.75);
}

// A plan always names a valid share of the wide node's slots, even where the costs are infinite
// or NaN (a box of infinite extent), and a cover by one root is the node itself.
TEST(WideCollapse, PlansStayValidOnInfiniteAndNanCosts) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double area : {0.0, 1.0, inf, nan})
    for (double child : {0.0, 2.0, inf, nan}) {
      detail::CollapseCosts l, r, out;
      for (double& f : l.forest) f = child;
      const std::uint32_t plan = detail::collapse_plan(area, l, r, out);
      EXPECT_GE(detail::plan_wide_share(plan), 1u);
      EXPECT_LE(detail::plan_wide_share(plan), 3u);
      EXPECT_EQ(detail::plan_cover_share(plan, 1), 0u);
      for (std::uint32_t k = 2; k <= 4; ++k) EXPECT_LT(detail::plan_cover_share(plan, k), k);
    }
}

}  // namespace
}  // namespace meshdev
