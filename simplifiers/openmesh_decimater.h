#pragma once
// OpenMesh 9.0 DecimaterT backends: halfedge collapse with endpoint placement (the surviving
// vertex keeps its position and all its attributes), priority = ModQuadricT (area-weighted plane
// quadrics, Garland & Heckbert 1997, evaluated at the endpoint).
//   openmesh-quadric    ModQuadric only                               (ProgMesh-like role)
//   openmesh-hausdorff  ModQuadric + ModHausdorff (one-sided global bound: every removed
//                       original vertex stays within `tolerance` of the simplified surface)
//                                                                     (Jade-like role)
//   openmesh-normal     ModQuadric + ModNormalFlipping + ModNormalDeviation
// Boundary vertices collapse only along the boundary; there are no boundary quadrics.
// This header does not include OpenMesh; when the library is compiled out the registry lists
// these names as unavailable.
#include <string>
#include <vector>

#include "simplifiers/simplifier.h"

namespace meshdev {

enum class OpenMeshVariant { kQuadric, kHausdorff, kNormal };

struct OpenMeshDecimaterOptions {
  // openmesh-hausdorff: the bound. In % of the input's bbox diagonal when tolerance_percent is
  // true (CLI: tolerance=0.5%), else absolute in file units (CLI: tolerance=0.002).
  double tolerance = 0.5;
  bool tolerance_percent = true;
  // openmesh-normal: ModNormalFlipping refuses collapses turning a one-ring face normal by more
  // than this (degrees, in (0, 180]).
  double max_normal_flip_deg = 45.0;
  // openmesh-normal: ModNormalDeviation keeps the cone of original normals each face stands for
  // within this full angle (degrees, in (0, 180]).
  double max_normal_deviation_deg = 30.0;
};

class OpenMeshDecimater : public Simplifier {
 public:
  explicit OpenMeshDecimater(OpenMeshVariant variant, OpenMeshDecimaterOptions options = {});

  std::string name() const override;
  std::string description() const override;
  std::string role() const override;
  std::string keeps() const override;
  bool available() const override { return true; }
  std::vector<OptionInfo> options() const override;
  void set_option(const std::string& key, const std::string& value) override;

  const OpenMeshDecimaterOptions& settings() const { return options_; }
  OpenMeshDecimaterOptions& settings() { return options_; }

  // One decimate_to_faces(0, target) run. kTargetNotReached when the modules stop it early;
  // kFailed when OpenMesh refuses input faces (non-manifold) or initialize() fails.
  // O(F log F) plus the modules' cost (Hausdorff: proportional to the removed points per ring).
  SimplifyResult simplify(const TriMesh& mesh, const SimplifyRequest& request) override;

  // One run down to the smallest target; an Observer snapshots the mesh when the face count
  // first drops to each target. Identical to separate runs; wall_seconds of each result is the
  // time from the start of the run to its snapshot.
  std::vector<SimplifyResult> simplify_sweep(const TriMesh& mesh,
                                             const std::vector<SimplifyRequest>& requests) override;

 private:
  OpenMeshVariant variant_;
  OpenMeshDecimaterOptions options_;
};

}  // namespace meshdev
