#pragma once
// The BVH build's face records (TriangleBvh::build): each face's box in the float frame, rounded
// outwards, and the boxes' and centres' bounds. Two versions with the same output, bit for bit:
// the baseline (metric/face_boxes.cpp, one face at a time) and an AVX2 version (metric/
// face_boxes_avx2.cpp, its own translation unit compiled with -mavx2, entered only where
// simd_level() is not kBaseline: four faces in the four double lanes, the same operations).
#include <cstdint>
#include <limits>

#include "metric/leaf_blocks.h"

namespace meshdev::detail {

// One face's box in the float frame, 32 bytes: lo rounded down and hi rounded up from the frame
// coordinates in double (so boxes made of them are conservative), with the face index's bits in
// lane 3 of lo and 0 in lane 3 of hi.
struct alignas(16) FaceBox {
  float lo[4];
  float hi[4];
};

// Bounds of boxes as SSE lanes (x, y, z, and a lane 3 carried along and never read): lo the
// lane-wise minimum, hi the maximum.
struct alignas(16) LaneBounds {
  float lo[4] = {kInf, kInf, kInf, kInf};
  float hi[4] = {-kInf, -kInf, -kInf, -kInf};

 private:
  static constexpr float kInf = std::numeric_limits<float>::infinity();
};

// The least and the largest coordinate, per axis, of the corners read (absolute units, NaN
// skipped as BoundingBox::extend skips it).
struct CornerBounds {
  double lo[3] = {kInf, kInf, kInf};
  double hi[3] = {-kInf, -kInf, -kInf};

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
};

// Writes out[f - begin] for the faces f in [begin, end) of a mesh given as raw arrays
// (`positions`, 3 doubles per vertex; `corners`, 3 vertex indices per face): per axis the least
// and the largest frame coordinate of its corners (frame.origin, frame.scale as in
// fill_leaf_block), round_down_to_float and round_up_to_float of them. Extends, face by face in
// order, `boxes` by (lo, hi) and `centres` by lo + hi (twice the box centre), each with SSE's
// min and max (the second operand where either is NaN), and `corner_bounds` by the corners'
// coordinates. Preconditions: indices within the arrays, out has end - begin records.
// O(end - begin).
void face_boxes(const double* positions, const std::uint32_t* corners, std::uint32_t begin,
                std::uint32_t end, const FrameMap& frame, FaceBox* out, LaneBounds& boxes,
                LaneBounds& centres, CornerBounds& corner_bounds);
// The same, bit for bit. Precondition: the CPU runs AVX2 (simd_level() != kBaseline); only in
// builds with MESHDEV_X86_KERNELS.
void face_boxes_avx2(const double* positions, const std::uint32_t* corners, std::uint32_t begin,
                     std::uint32_t end, const FrameMap& frame, FaceBox* out, LaneBounds& boxes,
                     LaneBounds& centres, CornerBounds& corner_bounds);

}  // namespace meshdev::detail
