#pragma once
// The bins of faces' centres along one axis: the first pass of each binned SAH split of the BVH
// build (TriangleBvh::build), which then adds each face's box to its bin and partitions the faces
// by the bins stored here. Two versions with the same output: the baseline (metric/
// centre_bins.cpp, one face at a time in double) and an AVX2 version (metric/
// centre_bins_avx2.cpp, its own translation unit compiled with -mavx2, entered only where
// simd_level() is not kBaseline: four faces in the four double lanes, the same operations).
#include <cstdint>

#include "metric/face_boxes.h"

namespace meshdev::detail {

// bins[i] for i < count, the bin of face box i among `bin_count` bins along `axis`: with key =
// boxes[i].lo[axis] + boxes[i].hi[axis] in float (twice the box centre; NaN counts as 0) and t =
// (double(key) - lo) * scale in double, bin_count - 1 where t >= bin_count - 1, the integer part
// of t where 0 < t < bin_count - 1, and 0 otherwise (t <= 0 or NaN). Units: the float frame's
// (lo and 1 / scale in units of twice the frame's coordinates). Preconditions: 0 <= axis < 3,
// 1 <= bin_count <= 256. O(count).
void centre_bins(const FaceBox* boxes, std::uint32_t count, int axis, double lo, double scale,
                 int bin_count, std::uint8_t* bins);
// The same, bin for bin. Precondition: the CPU runs AVX2 (simd_level() != kBaseline); only in
// builds with MESHDEV_X86_KERNELS.
void centre_bins_avx2(const FaceBox* boxes, std::uint32_t count, int axis, double lo, double scale,
                      int bin_count, std::uint8_t* bins);

}  // namespace meshdev::detail
