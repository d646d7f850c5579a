#pragma once
// A bounding-volume hierarchy over a triangle mesh for exact nearest-point queries with ties.
//
// Build: binned SAH (16 bins) on triangle centroids, leaves of at most 4 triangles.
//        O(F log F) time, O(F) memory (about 2F/4 nodes of 56 bytes plus 4 bytes per face).
// Query: best-first descent, nearer child first; a subtree is pruned only when its box is farther
//        than the current tie limit, so every candidate the brute-force oracle would keep is
//        visited and the result is identical to it. O(log F) expected near the surface, O(F)
//        worst case. Distances in double throughout.
// Ref: Wald, "On fast construction of SAH-based bounding volume hierarchies" (2007) for binning.
#include <cstdint>
#include <vector>

#include "metric/nearest_point.h"

namespace meshdev {

class TriangleBvh final : public NearestPointIndex {
 public:
  TriangleBvh(const TriMesh& target, const TieOptions& ties = {});
  std::string name() const override { return "bvh"; }
  double find(const Vec3& p, const QueryHint& hint, std::vector<SurfaceHit>& ties) const override;

  std::size_t node_count() const { return nodes_.size(); }
  std::size_t memory_bytes() const;
  int depth() const { return depth_; }

 private:
  struct Node {
    double lo[3], hi[3];
    std::uint32_t index;  // inner: first of two consecutive children; leaf: first slot in faces_
    std::uint32_t count;  // 0 for an inner node, else the number of faces in the leaf
  };

  void build();

  detail::FaceEvaluator eval_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> faces_;  // face ids in leaf order
  int depth_ = 0;
};

}  // namespace meshdev
