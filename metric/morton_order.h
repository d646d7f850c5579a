#pragma once
// The order of a run of points along a Morton (Z-order) curve.
//
// Consecutive points of that order are near each other, which is what the nearest-point indices
// need from a batch (TriangleBvh::find_batch answers near-by queries in packets and starts each
// query from the previous one's face): samples generated face by face are near each other only
// up to their face's size, and Monte Carlo samples inside a face come in random order.
//
// Codes: 21 bits per axis on a cubic grid over a box the caller gives (for compute_deviations,
// the reference mesh's box, which holds all its samples, so a run cut from a set already sorted
// along that curve is recognised as sorted), interleaved x-y-z (x in the lowest bit). A run is
// sorted by the 30 highest bits in which its codes differ (finer bits keep the input order).
// Deterministic. Ref: Morton, "A computer oriented geodetic data base..." (IBM, 1966).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "metric/mesh.h"

namespace meshdev {

// Writes to `order` the permutation of [0, n) that visits points[0..n) in Morton order of their
// cells in `box`; `keys` is scratch. The identity if the codes are already non-decreasing, or if
// the box is empty or not finite. Points outside the box (or NaN) are clamped to it.
// O(n): a check, then a radix sort of 4 passes; n < 2^32.
void morton_order(const Vec3* points, std::size_t n, const BoundingBox& box,
                  std::vector<std::uint32_t>& order, std::vector<std::uint64_t>& keys);

}  // namespace meshdev
