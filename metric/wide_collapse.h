#pragma once
// The collapse of a binary BVH into 4-wide nodes with the least SAH cost (TriangleBvh::build):
// a dynamic programme over the binary tree, bottom up, after Ylitie, Karras and Laine, "Efficient
// incoherent ray traversal on GPUs through compressed wide BVHs" (HPG 2017). The cost of a wide
// node is its box's half area (the chance that a query reaches it, each visit testing its four
// child boxes at once); the leaves cost nothing, as every collapse keeps the same leaves. Each
// binary node gets a plan of 8 bits that says, for a cover of its subtree by at most k roots (a
// root: a leaf, or a wide node of its own), whether the node is the one root or how many of the
// k roots its left child takes. The plan keeps children in order, so the leaves keep their order.
#include <cstdint>

namespace meshdev::detail {

// The least costs of a binary subtree: forest[k - 1], the least summed half area of the wide
// nodes when the subtree is covered by at most k roots, k = 1 .. 4. A leaf's are 0.
struct CollapseCosts {
  double forest[4] = {0, 0, 0, 0};
};

// Set in every plan, so a plan is never 0 nor a small count.
constexpr std::uint32_t kCollapsePlanned = 0x100;

// The plan of an inner binary node whose box has half area `half_area` (any unit, >= 0), from its
// children's costs; fills `out` with the node's. Ties go to the left child's smaller share, and a
// forest of k > 1 roots keeps the node as its one root only where that costs strictly less.
// O(1).
std::uint32_t collapse_plan(double half_area, const CollapseCosts& left, const CollapseCosts& right,
                            CollapseCosts& out);

// How a plan covers its node with at most k roots (k = 1 .. 4): 0, the node is the one root;
// else the left child's share a of the roots (the right child's k - a). k = 1 always gives 0.
inline std::uint32_t plan_cover_share(std::uint32_t plan, std::uint32_t k) {
  return k >= 2 ? plan >> (2 * k - 2) & 3u : 0u;
}
// The left child's share a of the node's 4 child slots when it is a wide node (1 .. 3; the right
// child's 4 - a).
inline std::uint32_t plan_wide_share(std::uint32_t plan) {
  return plan & 3u;
}

// Calls emit(root) for each root, in order, of the cover of binary node `node` by at most k roots
// that the plans give. inner(node, left, right, plan): false for a leaf; for an inner node, true
// with its children and plan set. O(k).
template <class Inner, class Emit>
void for_each_cover_root(const Inner& inner, std::uint32_t node, std::uint32_t k,
                         const Emit& emit) {
  std::uint32_t left = 0, right = 0, plan = 0;
  const std::uint32_t share = inner(node, left, right, plan) ? plan_cover_share(plan, k) : 0;
  if (share == 0) {
    emit(node);
    return;
  }
  for_each_cover_root(inner, left, share, emit);
  for_each_cover_root(inner, right, k - share, emit);
}

// Calls emit(child) for each child, in order, of the wide node that inner binary node `node`
// becomes (2 to 4 of them). Precondition: inner(node, ...) is true. O(1).
template <class Inner, class Emit>
void for_each_wide_child(const Inner& inner, std::uint32_t node, const Emit& emit) {
  std::uint32_t left = 0, right = 0, plan = 0;
  inner(node, left, right, plan);
  const std::uint32_t share = plan_wide_share(plan);
  for_each_cover_root(inner, left, share, emit);
  for_each_cover_root(inner, right, 4 - share, emit);
}

}  // namespace meshdev::detail
