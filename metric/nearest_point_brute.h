#pragma once
// The brute-force nearest-point oracle: tests every face. O(F) per query, no build.
// The test oracle for every faster index (the same FaceEvaluator, so the same numbers).
#include "metric/nearest_point.h"

namespace meshdev {

class NearestPointBrute final : public NearestPointIndex {
 public:
  NearestPointBrute(const TriMesh& target, const TieOptions& ties = {});
  std::string name() const override { return "brute-force"; }
  double find(const Vec3& p, const QueryHint& hint, std::vector<SurfaceHit>& ties) const override;

 private:
  detail::FaceEvaluator eval_;
};

}  // namespace meshdev
