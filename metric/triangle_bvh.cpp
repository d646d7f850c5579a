#include "metric/triangle_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace meshdev {
namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kLeafSize = 4;
constexpr int kMaxDepth = 60;  // deeper subtrees become (larger) leaves

struct Box {
  double lo[3] = {+1e300, +1e300, +1e300};
  double hi[3] = {-1e300, -1e300, -1e300};
  void extend(const Box& b) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], b.lo[k]);
      hi[k] = std::max(hi[k], b.hi[k]);
    }
  }
  void extend(const Vec3& p) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  double half_area() const {
    if (lo[0] > hi[0]) return 0.0;
    const double dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    return dx * dy + dy * dz + dz * dx;
  }
};

// Squared distance from p to an axis-aligned box (0 inside).
inline double box_sq_distance(const Vec3& p, const double lo[3], const double hi[3]) {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double below = lo[k] - p[k], above = p[k] - hi[k];
    const double d = below > 0.0 ? below : (above > 0.0 ? above : 0.0);
    d2 += d * d;
  }
  return d2;
}

// Boxes may be slightly closer than rounding makes the triangles inside them; prune only beyond
// this factor so no candidate the oracle keeps can be missed.
constexpr double kPruneSlack = 1.0 + 1e-12;

}  // namespace

TriangleBvh::TriangleBvh(const TriMesh& target, const TieOptions& ties) : eval_(target, ties) {
  build();
}

std::size_t TriangleBvh::memory_bytes() const {
  return nodes_.size() * sizeof(Node) + faces_.size() * sizeof(std::uint32_t);
}

void TriangleBvh::build() {
  const TriMesh& m = *eval_.mesh;
  const auto n = static_cast<std::uint32_t>(m.faces.size());
  std::vector<Box> boxes(n);
  std::vector<Vec3> centroids(n);
  for (std::uint32_t f = 0; f < n; ++f) {
    for (std::uint32_t v : m.faces[f]) boxes[f].extend(m.positions[v]);
    for (int k = 0; k < 3; ++k) centroids[f][k] = 0.5 * (boxes[f].lo[k] + boxes[f].hi[k]);
  }
  faces_.resize(n);
  std::iota(faces_.begin(), faces_.end(), 0u);
  nodes_.clear();
  nodes_.reserve(2 * (n / kLeafSize + 1));
  nodes_.push_back({});

  struct Task {
    std::uint32_t node, begin, end;
    int depth;
  };
  std::vector<Task> stack{{0, 0, n, 1}};
  while (!stack.empty()) {
    const Task task = stack.back();
    stack.pop_back();
    depth_ = std::max(depth_, task.depth);
    Box bounds, centroid_bounds;
    for (std::uint32_t i = task.begin; i < task.end; ++i) {
      bounds.extend(boxes[faces_[i]]);
      centroid_bounds.extend(centroids[faces_[i]]);
    }
    Node& node = nodes_[task.node];
    std::copy(bounds.lo, bounds.lo + 3, node.lo);
    std::copy(bounds.hi, bounds.hi + 3, node.hi);
    const std::uint32_t count = task.end - task.begin;

    // Split axis: the widest extent of the centroids.
    int axis = 0;
    double extent = -1.0;
    for (int k = 0; k < 3; ++k)
      if (centroid_bounds.hi[k] - centroid_bounds.lo[k] > extent) {
        extent = centroid_bounds.hi[k] - centroid_bounds.lo[k];
        axis = k;
      }
    if (count <= kLeafSize || task.depth >= kMaxDepth) {
      node.index = task.begin;
      node.count = count;
      continue;
    }

    // All centroids equal (extent 0): split by position in the list, which bounds leaf sizes.
    std::uint32_t mid = task.begin + count / 2;
    if (extent > 0.0) {
      // Binned SAH.
      Box bin_box[kBins];
      std::uint32_t bin_count[kBins] = {};
      const double scale = kBins / extent;
      auto bin_of = [&](std::uint32_t f) {
        int b = static_cast<int>((centroids[f][axis] - centroid_bounds.lo[axis]) * scale);
        return std::clamp(b, 0, kBins - 1);
      };
      for (std::uint32_t i = task.begin; i < task.end; ++i) {
        const int b = bin_of(faces_[i]);
        bin_box[b].extend(boxes[faces_[i]]);
        ++bin_count[b];
      }
      double right_area[kBins];
      std::uint32_t right_count[kBins];
      Box acc;
      std::uint32_t acc_count = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.extend(bin_box[b]);
        acc_count += bin_count[b];
        right_area[b] = acc.half_area();
        right_count[b] = acc_count;
      }
      Box left;
      std::uint32_t left_count = 0;
      double best_cost = std::numeric_limits<double>::infinity();
      int best_split = -1;
      for (int b = 1; b < kBins; ++b) {
        left.extend(bin_box[b - 1]);
        left_count += bin_count[b - 1];
        if (left_count == 0 || right_count[b] == 0) continue;
        const double cost = left.half_area() * left_count + right_area[b] * right_count[b];
        if (cost < best_cost) {
          best_cost = cost;
          best_split = b;
        }
      }
      if (best_split > 0) {
        auto it = std::partition(faces_.begin() + task.begin, faces_.begin() + task.end,
                                 [&](std::uint32_t f) { return bin_of(f) < best_split; });
        mid = static_cast<std::uint32_t>(it - faces_.begin());
      }
      if (mid == task.begin || mid == task.end) {
        mid = task.begin + count / 2;
        std::nth_element(faces_.begin() + task.begin, faces_.begin() + mid,
                         faces_.begin() + task.end, [&](std::uint32_t x, std::uint32_t y) {
                           return centroids[x][axis] < centroids[y][axis] ||
                                  (centroids[x][axis] == centroids[y][axis] && x < y);
                         });
      }
    }
    const auto left_child = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({});
    nodes_.push_back({});
    Node& parent = nodes_[task.node];  // re-fetch: push_back may have reallocated
    parent.index = left_child;
    parent.count = 0;
    stack.push_back({left_child + 1, mid, task.end, task.depth + 1});
    stack.push_back({left_child, task.begin, mid, task.depth + 1});
  }
}

double TriangleBvh::find(const Vec3& p, const QueryHint& hint,
                         std::vector<SurfaceHit>& ties) const {
  ties.clear();
  double best_sq = std::numeric_limits<double>::infinity();
  double limit = best_sq, limit_dist = best_sq;
  // A face identical to the query's source triangle counts as distance 0 however far rounding
  // put the query from it (FaceEvaluator::evaluate), so such faces are never pruned: the search
  // never narrows below the reach of that check.
  const double floor_sq = hint.source != nullptr ? eval_.exact_check_sq : 0.0;
  const double floor_dist = std::sqrt(floor_sq);
  auto consider = [&](std::uint32_t f) {
    if (eval_.rejects(p, f, std::max(limit_dist, floor_dist))) return;
    SurfaceHit h = eval_.evaluate(p, f, hint);
    if (h.sq_distance > limit) return;
    if (h.sq_distance < best_sq) {
      best_sq = h.sq_distance;
      limit = eval_.limit_sq(best_sq);
      limit_dist = std::sqrt(limit);
    }
    ties.push_back(h);
  };
  if (hint.start_face != kNoFace && hint.start_face < eval_.mesh->faces.size())
    consider(hint.start_face);

  struct Item {
    std::uint32_t node;
    double sq;
  };
  // The build caps the depth, so the stack (at most depth + 1 entries) fits on the stack.
  Item stack[kMaxDepth + 2];
  int top = 0;
  stack[top++] = {0, box_sq_distance(p, nodes_[0].lo, nodes_[0].hi)};
  while (top > 0) {
    const Item item = stack[--top];
    const double prune = std::max(limit, floor_sq) * kPruneSlack;
    if (item.sq > prune) continue;
    const Node& node = nodes_[item.node];
    if (node.count > 0) {
      for (std::uint32_t i = node.index; i < node.index + node.count; ++i)
        if (faces_[i] != hint.start_face) consider(faces_[i]);
      continue;
    }
    const Node& l = nodes_[node.index];
    const Node& r = nodes_[node.index + 1];
    const double dl = box_sq_distance(p, l.lo, l.hi);
    const double dr = box_sq_distance(p, r.lo, r.hi);
    // Push the farther child first so the nearer one is visited first.
    if (dl <= dr) {
      if (dr <= prune) stack[top++] = {node.index + 1, dr};
      if (dl <= prune) stack[top++] = {node.index, dl};
    } else {
      if (dl <= prune) stack[top++] = {node.index, dl};
      if (dr <= prune) stack[top++] = {node.index + 1, dr};
    }
  }
  // Keep the candidates within the final tie limit, in face order (as the oracle does).
  detail::keep_ties(ties, limit);
  return std::sqrt(best_sq);
}

}  // namespace meshdev
