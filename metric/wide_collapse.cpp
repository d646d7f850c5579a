#include "metric/wide_collapse.h"

#include <cassert>
#include <limits>

namespace meshdev::detail {

std::uint32_t collapse_plan(double half_area, const CollapseCosts& left, const CollapseCosts& right,
                            CollapseCosts& out) {
  // pair[k]: the least cost of covering the two children with at most k roots together (each at
  // least one), and share[k] the left child's part of them. The costs never grow with k, so the
  // best cover takes all k.
  double pair[5] = {0, 0, 0, 0, 0};
  std::uint32_t share[5] = {1, 1, 1, 1, 1};  // kept where every cost is infinite or NaN
  for (std::uint32_t k = 2; k <= 4; ++k) {
    pair[k] = std::numeric_limits<double>::infinity();
    for (std::uint32_t a = 1; a < k; ++a) {
      const double cost = left.forest[a - 1] + right.forest[k - a - 1];
      if (cost < pair[k]) {
        pair[k] = cost;
        share[k] = a;
      }
    }
  }
  const double wide = half_area + pair[4];
  out.forest[0] = wide;
  std::uint32_t plan = kCollapsePlanned | share[4];
  for (std::uint32_t k = 2; k <= 4; ++k) {
    const bool one_root = wide < pair[k];
    out.forest[k - 1] = one_root ? wide : pair[k];
    plan |= (one_root ? 0u : share[k]) << (2 * k - 2);
  }
  assert(plan_wide_share(plan) >= 1 && plan_wide_share(plan) <= 3);
  return plan;
}

}  // namespace meshdev::detail
