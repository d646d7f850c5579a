#pragma once
// A hashed uniform grid over a triangle mesh in front of the BVH: the paper's (§4) and Metro's
// structure for many spatially coherent queries very near the surface, made exact.
//
// Build: cell size h = sqrt(area / F) (about one triangle width, doubled while the references
//        exceed 16 F); every triangle listed in the cells its bounding box overlaps; occupied
//        cells in an open-addressing hash table. O(F) expected time. Memory: the BVH's plus
//        the table and references, 77-227 bytes per face in all on the meshes measured
//        (docs/performance-log.md §3), which is why the BVH alone stays the default.
// Query: test the triangles listed in p's cell. If the tie limit around the best one found fits
//        inside that cell, every triangle that can be a tie overlaps the cell and was tested, so
//        the answer is exact; otherwise (far queries, cell borders, empty cells) the BVH answers,
//        seeded with the best face found. Either way the result equals the brute-force oracle.
//        O(triangles per cell) for the fast path.
// Ref: Cignoni, Rocchini, Scopigno, "Metro: measuring error on simplified surfaces" (1998).
#include <cstdint>
#include <vector>

#include "metric/triangle_bvh.h"

namespace meshdev {

class TriangleGrid final : public NearestPointIndex {
 public:
  TriangleGrid(const TriMesh& target, const TieOptions& ties = {}, int threads = 0);
  std::string name() const override { return "grid+bvh"; }
  double find(const Vec3& p, const QueryHint& hint, std::vector<SurfaceHit>& ties) const override;

  std::size_t memory_bytes() const;
  std::size_t cell_count() const { return cell_count_; }
  double cell_size() const { return h_; }

 private:
  struct Slot {
    std::uint64_t key = kEmpty;        // packed cell coordinates, kEmpty if unused
    std::uint32_t begin = 0, end = 0;  // range in refs_
  };
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};

  const Slot* lookup(std::uint64_t key) const;

  detail::FaceEvaluator eval_;
  TriangleBvh bvh_;
  Vec3 origin_;
  double h_ = 1, inv_h_ = 1;
  std::int64_t dims_[3] = {0, 0, 0};
  double slack_ = 0;  // absolute rounding allowance for the cell-containment test
  std::vector<Slot> table_;
  std::vector<std::uint32_t> refs_;
  std::size_t cell_count_ = 0;
};

}  // namespace meshdev
