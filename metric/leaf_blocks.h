#pragma once
// The BVH's leaf blocks (TriangleBvh::build): up to four faces in SIMD lanes, their corners in the
// float frame and the cull margin factor of each. Two versions with the same output, bit for
// bit: the baseline (metric/leaf_blocks.cpp, one face at a time in double) and an AVX2 version
// (metric/leaf_blocks_avx2.cpp, its own translation unit compiled with -mavx2, entered only where
// simd_level() is not kBaseline: the block's four faces in the four double lanes, the same
// operations in the same order, no FMA).
#include <cstdint>

#include "metric/plane_bounds.h"

namespace meshdev::detail {

// Up to four triangles: corners [corner][axis][lane] (float frame, rounded to nearest), the cull
// margin factor per lane (+inf: never culled by the triangle bound) and the face ids (kNoFace:
// empty). Empty lanes are last, with corners 0.
struct alignas(16) LeafBlock {
  float corner[3][3][4];
  float margin[4];
  std::uint32_t face[4];
};

constexpr double kFloatUnit = 0x1p-24;  // unit roundoff of float (round to nearest)
// Margin constant of the triangle bound (see TriangleBvh's header and docs/metric.md): the
// first-order rounding analysis gives about 20 u (1 + kappa) (|ap| + |bp| + |cp|); 64 leaves a
// factor 3.
constexpr double kMarginConstant = 64.0;

// The float frame of a build: a point x maps to (x - origin) * scale, axis by axis, in double.
struct FrameMap {
  double origin[3];
  double scale;
};

// What a block adds to the build's totals.
struct LeafBlockSums {
  // The faces' longest edges (frame units), summed in lane order.
  double edge_sum = 0;
  // The largest squared distance of a rounded corner from its frame point.
  double corner_error2 = 0;
};

// Fills `out` with faces face_ids[0 .. count - 1] of a mesh given as raw arrays: `positions`, 3
// doubles per vertex; `corners`, 3 vertex indices per face. Lane k: the frame of each corner
// rounded to float, the margin factor round_up_to_float(kMarginConstant * kFloatUnit * (2 +
// kappa)) with kappa = |ab| |ac| / |ab x ac| of the rounded corners (+inf where |ab x ac|^2 <
// kMinCullNormal2 or kappa > kMaxCullKappa, or NaN), and the face id; lanes from count on empty.
// Returns the lanes' longest edges summed in lane order (sqrt of the largest of |ab|^2, |ac|^2,
// |bc|^2, std::max's choice) and the largest squared corner error (NaN errors ignored).
// Preconditions: 1 <= count <= 4, indices within the arrays. O(1).
LeafBlockSums fill_leaf_block(const double* positions, const std::uint32_t* corners,
                              const std::uint32_t* face_ids, std::uint32_t count,
                              const FrameMap& frame, LeafBlock& out);
// The same, bit for bit, in AVX2 lanes. Precondition: the CPU runs AVX2 (simd_level() !=
// kBaseline); only in builds with MESHDEV_X86_KERNELS.
LeafBlockSums fill_leaf_block_avx2(const double* positions, const std::uint32_t* corners,
                                   const std::uint32_t* face_ids, std::uint32_t count,
                                   const FrameMap& frame, LeafBlock& out);

}  // namespace meshdev::detail
