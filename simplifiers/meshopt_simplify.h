#pragma once
// meshoptimizer 0.18 backends (Debian libmeshoptimizer-dev):
//   meshopt         meshopt_simplify: edge collapse onto existing vertices with a quadric error,
//                   topology and UV seams kept, border lockable
//   meshopt-sloppy  meshopt_simplifySloppy: vertex clustering on a grid, ignores topology
// Both pick a subset of the input vertices (vertices never move), so per-vertex channels are
// copied exactly. Per-corner channels are kept by unwelding: every distinct (vertex, corner
// values) pair becomes one meshopt vertex, which meshopt 0.18 treats as a seam; the output is
// welded back to our vertices. Per-face channels are dropped (output triangles are new).
// This header does not include meshoptimizer.
#include <string>
#include <vector>

#include "simplifiers/simplifier.h"

namespace meshdev {

enum class MeshoptVariant { kSimplify, kSloppy };

struct MeshoptOptions {
  // Largest error allowed, relative to the mesh extent (meshopt_simplifyScale). 1.0 means "no
  // bound": stop only at the target count. Smaller values can stop early (kTargetNotReached).
  double target_error = 1.0;
  // meshopt only: meshopt_SimplifyLockBorder (border vertices never move or collapse).
  bool lock_border = false;
};

class MeshoptSimplifier : public Simplifier {
 public:
  explicit MeshoptSimplifier(MeshoptVariant variant, MeshoptOptions options = {});

  std::string name() const override;
  std::string description() const override;
  std::string role() const override;
  std::string keeps() const override;
  bool available() const override { return true; }
  // meshopt 0.18 does not refuse collapses that leave collinear (zero-area) triangles on flat
  // regions; sloppy clustering also ignores topology (non-manifold edges possible).
  OutputGuarantees guarantees() const override;
  std::vector<OptionInfo> options() const override;
  void set_option(const std::string& key, const std::string& value) override;

  const MeshoptOptions& settings() const { return options_; }
  MeshoptOptions& settings() { return options_; }

  // One meshopt call on float positions. backend_error = meshopt's result_error (relative to
  // the extent). Triangles that weld back onto a repeated vertex are dropped (counted in the
  // message). O(F log F) time, O(V + F) memory.
  SimplifyResult simplify(const TriMesh& mesh, const SimplifyRequest& request) override;

 private:
  MeshoptVariant variant_;
  MeshoptOptions options_;
};

}  // namespace meshdev
