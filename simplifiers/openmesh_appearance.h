#pragma once
// openmesh-appearance: OpenMesh halfedge collapses driven by our own Decimater module with a
// generalized quadric over position AND per-vertex attributes (Garland & Heckbert 1998,
// "Simplifying surfaces with color and texture using quadric error metrics").
//
//   every vertex v -> a point s(v) in R^(3+k): position / bbox diagonal, then each per-vertex
//                     channel (colour, UV, normal, scalars / their range) times its weight
//   every face     -> the GH98 quadric of the plane through its three points in R^(3+k),
//                     weighted by its area; open borders add position-only planes (weight
//                     boundary_weight x edge length^2) so they do not erode
//   collapse v0->v1: Q = Q0 + Q1; placement = argmin Q when the (3+k)x(3+k) solve is
//                     well-conditioned and lands near the edge, else the better endpoint; a
//                     placement that turns a one-ring face normal by more than max_flip_deg or
//                     makes a zero-area face is refused (checked at the placed position)
//   after it:        v1 moves there and takes the attributes of the placed point (colours
//                     clamped to [0,1], normals renormalised)
// A small driver of ours (not DecimaterT) re-checks every popped candidate against the current
// mesh, so priorities made stale by a moved vertex never let a flip through.
// Per-corner channels keep their seams (no collapse across a seam, corners take values their
// vertex had); per-face channels follow their surviving faces.
// This header does not include OpenMesh.
#include <string>
#include <vector>

#include "simplifiers/simplifier.h"

namespace meshdev {

struct OpenMeshAppearanceOptions {
  // Weights of the attribute coordinates in the quadric, per channel kind (0 = not in the
  // quadric: the channel is copied from the surviving endpoint; normals are then recomputed).
  // Positions are divided by the bbox diagonal, colours are in [0,1], UVs as stored, normals unit,
  // scalar channels divided by their range, so one weight scale fits every mesh.
  double color_weight = 0.1;
  double texcoord_weight = 0.1;
  double normal_weight = 0.05;
  double scalar_weight = 0.05;
  // Weight of the border planes (position only), times the squared border edge length.
  double boundary_weight = 100.0;
  // true: place at the quadric's minimum when valid (vertices move, attributes interpolated);
  // false: endpoint placement, v1 keeps its position and values exactly (vertices fixed).
  bool optimal = true;
  // A collapse may not turn any remaining one-ring face normal by more than this (degrees).
  double max_flip_deg = 60.0;
};

class OpenMeshAppearance : public Simplifier {
 public:
  explicit OpenMeshAppearance(OpenMeshAppearanceOptions options = {});

  std::string name() const override { return "openmesh-appearance"; }
  std::string description() const override;
  std::string role() const override;
  std::string keeps() const override;
  OutputGuarantees guarantees() const override;
  std::vector<OptionInfo> options() const override;
  void set_option(const std::string& key, const std::string& value) override;

  const OpenMeshAppearanceOptions& settings() const { return options_; }
  OpenMeshAppearanceOptions& settings() { return options_; }

  // One run to the target. kTargetNotReached when no legal collapse is left (flip limit, seams,
  // topology); kFailed when OpenMesh refuses input faces (non-manifold).
  // O(F log F x (3+k)^3) time, O(V (3+k)^2) memory.
  SimplifyResult simplify(const TriMesh& mesh, const SimplifyRequest& request) override;

  // One run down to the smallest target with a snapshot at each target (identical to separate
  // runs); wall_seconds of each result is measured from the start of the run.
  std::vector<SimplifyResult> simplify_sweep(const TriMesh& mesh,
                                             const std::vector<SimplifyRequest>& requests) override;

 private:
  OpenMeshAppearanceOptions options_;
};

}  // namespace meshdev
