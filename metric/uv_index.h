#pragma once
// A 2D index over a mesh's triangles in texture space (u, v): which triangles contain a given
// (u, v), and the nearest UV point when none does. Used by Cohen's texture deviation (paper §2.3,
// Eq. 2), which needs F_b^-1(u, v): the point of mesh B with texture coordinates (u, v).
#include <array>
#include <cstdint>
#include <vector>

#include "metric/mesh.h"

namespace meshdev {

struct UvHit {
  std::uint32_t face = 0;
  std::array<double, 3> bary{1, 0, 0};  // on the face's corners, in corner order
  double uv_distance = 0;               // 0 when (u, v) is inside the face's UV triangle
};

class UvIndex {
 public:
  // Indexes `mesh`'s faces by their UV triangles (`texcoord`: dim 2, per vertex or per corner).
  // A uniform grid of about F cells over the UV bounding box; each face is listed in the cells its
  // UV bounding box overlaps. Throws InvalidInput if texcoord is not 2-D or the mesh has no faces.
  // O(F + total overlaps) time and memory.
  UvIndex(const TriMesh& mesh, const AttributeChannel& texcoord);

  // Every face whose UV triangle contains (u, v) (barycentrics >= -1e-9, so points on shared UV
  // edges are found in both faces), in face order, written to `out`. UV triangles of zero area are
  // never "containing" (their inverse map is undefined). O(faces listed in one cell).
  void containing(double u, double v, std::vector<UvHit>& out) const;

  // The face and point whose UV is nearest to (u, v) (Euclidean in UV; ties: lowest face index),
  // uv_distance set. Searches rings of cells outwards until no closer cell can remain. Expected
  // O(cells searched x faces per cell).
  UvHit nearest(double u, double v) const;

  std::size_t face_count() const { return uv_.size(); }

 private:
  struct Uv3 {
    double u[3], v[3];
  };
  std::vector<Uv3> uv_;
  double u0_ = 0, v0_ = 0, cell_u_ = 1, cell_v_ = 1;
  int nu_ = 1, nv_ = 1;
  std::vector<std::uint32_t> start_, items_;  // CSR: cell c lists items_[start_[c]..start_[c+1])

  int cell_u(double u) const;
  int cell_v(double v) const;
};

}  // namespace meshdev
