#include "metric/nearest_point_brute.h"

#include <cmath>
#include <limits>

namespace meshdev {

NearestPointBrute::NearestPointBrute(const TriMesh& target, const TieOptions& ties)
    : eval_(target, ties) {}

double NearestPointBrute::find(const Vec3& p, const QueryHint& hint,
                               std::vector<SurfaceHit>& ties) const {
  ties.clear();
  double best_sq = std::numeric_limits<double>::infinity();
  const auto n = static_cast<std::uint32_t>(eval_.mesh->faces.size());
  for (std::uint32_t f = 0; f < n; ++f) {
    SurfaceHit h = eval_.evaluate(p, f, hint);
    if (h.sq_distance < best_sq) best_sq = h.sq_distance;
    ties.push_back(h);
  }
  detail::keep_ties(ties, eval_.limit_sq(best_sq));
  return std::sqrt(best_sq);
}

}  // namespace meshdev
