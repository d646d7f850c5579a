#pragma once
// CGAL 5.5 Surface_mesh_simplification::edge_collapse backends, full edge collapse with optimal
// placement (the surviving vertex moves), stopped by a face-count predicate (CGAL 5.5 has none):
//   cgal-gh  GarlandHeckbert_plane_policies: plane quadrics (Garland & Heckbert 1997) with
//            boundary quadrics, optimal placement             (QSlim-like role)
//   cgal-lt  LindstromTurk cost and placement (Lindstrom & Turk 1998, memoryless)
// All CGAL includes live in cgal_edge_collapse.cpp (one heavy TU). This header does not include
// CGAL; when it is compiled out the registry lists these names as unavailable.
#include <string>
#include <vector>

#include "simplifiers/simplifier.h"

namespace meshdev {

enum class CgalPolicy { kGarlandHeckbert, kLindstromTurk };

struct CgalEdgeCollapseOptions {
  // cgal-gh: weight of the boundary quadrics (GarlandHeckbert_plane_policies' dm); larger keeps
  // open borders more tightly.
  double boundary_weight = 100.0;
};

class CgalEdgeCollapse : public Simplifier {
 public:
  explicit CgalEdgeCollapse(CgalPolicy policy, CgalEdgeCollapseOptions options = {});

  std::string name() const override;
  std::string description() const override;
  std::string role() const override;
  std::string keeps() const override;
  bool available() const override { return true; }
  // Optimal placement moves vertices: per-vertex values are the survivor's, not exact.
  OutputGuarantees guarantees() const override;
  std::vector<OptionInfo> options() const override;
  void set_option(const std::string& key, const std::string& value) override;

  // One edge_collapse run to the face target. kFailed when Surface_mesh refuses input faces
  // (non-manifold). Per-vertex channels are taken from the surviving vertex (which moved to the
  // optimal point, so they are approximate); per-vertex normals are recomputed from the faces;
  // per-corner and per-face channels are dropped. O(E log E).
  SimplifyResult simplify(const TriMesh& mesh, const SimplifyRequest& request) override;

 private:
  CgalPolicy policy_;
  CgalEdgeCollapseOptions options_;
};

}  // namespace meshdev
