#pragma once
// The order of a run of points along a Morton (Z-order) curve.
//
// Consecutive points of that order are near each other, which is what the nearest-point indices
// need from a batch (TriangleBvh::find_batch answers near-by queries in packets and starts each
// query from the previous one's face): samples generated face by face are near each other only
// up to their face's size, and Monte Carlo samples inside a face come in random order.
//
// Codes: 10 bits per axis on a cubic grid over the points' bounding box (cells 1/1024 of its
// largest extent), interleaved x-y-z; equal codes keep their input order. Deterministic.
// Ref: Morton, "A computer oriented geodetic data base..." (IBM, 1966).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "metric/vec3.h"

namespace meshdev {

// Writes to `order` the permutation of [0, n) that visits points[0..n) in Morton order;
// `keys` is scratch. The identity if the points are already in that order, or if their box is
// not finite (then nothing is sorted). O(n): a check, then a radix sort; n < 2^32.
void morton_order(const Vec3* points, std::size_t n, std::vector<std::uint32_t>& order,
                  std::vector<std::uint64_t>& keys);

}  // namespace meshdev
