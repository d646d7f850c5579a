#pragma once
// A 4-wide bounding-volume hierarchy over a triangle mesh for exact nearest-point queries with ties.
//
// Build: binned SAH (16 bins) on triangle centroids into a binary tree with leaves of at most 4
//        triangles, then collapsed into 4-wide nodes (the inner child of largest area is opened
//        until a node has 4 children). Boxes and triangle corners are stored in single precision,
//        4 per block (structure of arrays), in a frame centred on the mesh and scaled to [-1, 1].
//        O(F log F) time, subtrees built in parallel (OpenMP tasks); memory_bytes() is about
//        55-62 bytes per face.
// Query: depth-first, nearer child first, starting from the upper bound of hint.start_face. Four
//        boxes or four triangles are tested per step with SSE (metric/simd4.h). A box or a
//        triangle is skipped only when a conservative single-precision lower bound on its
//        distance exceeds the current tie limit; every face that survives is evaluated exactly in
//        double (detail::FaceEvaluator), so the distance and the tie set are those of the
//        brute-force oracle. O(log F) expected near the surface, O(F) worst case.
// Why float cannot change the result (docs/metric.md "Culling in single precision"):
//   boxes are rounded outwards; the query's own rounding and the corners' rounding are measured
//   and added to the radius; the triangle lower bound sqrt(h^2 + max_e out_e^2) (distance to the
//   supporting plane and to the edge half-planes) gets a margin 64 u (2 + kappa) (|ap|+|bp|+|cp|)
//   that covers its rounding error (u = 2^-24, kappa = |ab||ac| / |ab x ac|; offsets are
//   normalised before squaring, so nothing that matters underflows); slivers (kappa > 1e6),
//   triangles under ~1e-5 of the mesh and queries beyond 1e12 mesh sizes are never culled by it.
// Ref: Wald, "On fast construction of SAH-based bounding volume hierarchies" (2007) for binning;
//      Wald et al., "Getting rid of packets" (2008) and Embree for 4-wide nodes.
#include <cstdint>
#include <vector>

#include "metric/nearest_point.h"

namespace meshdev {

class TriangleBvh final : public NearestPointIndex {
 public:
  // threads: OpenMP threads for the build (0 = OpenMP's default); the structure is the same for
  // any thread count.
  TriangleBvh(const TriMesh& target, const TieOptions& ties = {}, int threads = 0);
  std::string name() const override { return "bvh"; }
  double find(const Vec3& p, const QueryHint& hint, std::vector<SurfaceHit>& ties) const override;

  std::size_t node_count() const { return nodes_.size(); }
  std::size_t leaf_count() const { return leaves_.size(); }
  // Bytes of the structure (nodes and leaf blocks), without the mesh it indexes.
  std::size_t memory_bytes() const;
  int depth() const { return depth_; }  // levels of 4-wide nodes, leaves included

 private:
  // Four child boxes, [axis][child]; child refs: a node index, kLeaf | leaf index, or kEmpty.
  struct alignas(16) Node {
    float lo[3][4];
    float hi[3][4];
    std::uint32_t child[4];
  };
  // Up to four triangles: corners [corner][axis][lane] (rounded to nearest), the cull margin
  // factor per lane (+inf: never culled by the triangle bound) and the face ids (kNoFace: empty).
  struct alignas(16) Leaf {
    float corner[3][3][4];
    float margin[4];
    std::uint32_t face[4];
  };

  void build(int threads);

  detail::FaceEvaluator eval_;
  Vec3 origin_;                // centre of the target's bounding box
  double scale_ = 1;           // float frame = (x - origin_) * scale_
  double corner_error_ = 0;    // max |float corner - exact corner| in the float frame
  std::uint32_t root_ = 0;     // child ref of the root
  std::vector<Node> nodes_;
  std::vector<Leaf> leaves_;
  int depth_ = 0;
};

}  // namespace meshdev
