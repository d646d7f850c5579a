#pragma once
// The packets' tree walk (TriangleBvh::gather_blocks): the leaf blocks of a 4-wide BVH whose
// boxes lie within reach of a box, with their boxes, breadth first; and each query's choice among
// them (blocks_near_point). Two versions of each with the same output, element for element: the
// baseline (SSE2 or plain code, metric/leaf_gather.cpp) and an AVX version
// (metric/leaf_gather_avx2.cpp, its own translation unit compiled with -mavx2, entered only where
// simd_level() is not kBaseline).
#include <cstddef>
#include <cstdint>

namespace meshdev::detail {

// A node of the 4-wide tree: four child boxes [axis][child] (float frame) and the child refs: a
// node index, kWideLeafBit | leaf block index, or kWideEmpty.
struct alignas(16) WideNode {
  float lo[3][4];
  float hi[3][4];
  std::uint32_t child[4];
};
constexpr std::uint32_t kWideLeafBit = 0x80000000u;
constexpr std::uint32_t kWideEmpty = 0xffffffffu;

// Where the gathered blocks go: block[i] (the leaf index, without kWideLeafBit) and its box
// lo[axis][i], hi[axis][i]. Each array needs room for max_blocks + 4 entries (a node writes four
// from the count on).
struct GatheredBlocks {
  std::uint32_t* block;
  float* lo[3];
  float* hi[3];
};

// The leaf blocks under inner node `root` whose boxes, and every ancestor's box, lie within
// squared distance `limit2` of [lo, hi] (all float frame; box_gap2's float arithmetic, metric/
// simd4.h: per axis the gap max(max(blo - qhi, qlo - bhi), 0), squared and summed in axis order;
// kept unless gap2 > limit2, so NaN gaps are kept). Breadth first: the nodes are opened in the
// order they were kept, a node's kept children in lane order, its leaf blocks appended to `out`
// and its inner children to `queue`. Returns the blocks' count, or max_blocks + 1 where more
// than max_blocks are within reach or more than queue_size nodes are (the walk stops there).
// `queue`: room for queue_size + 4 node refs (a node writes four from its tail).
// Preconditions: root an inner node. O(nodes opened).
//
// Breadth first rather than depth first because the next node opened does not depend on the
// node being opened (a depth-first stack's top does, through the count of children pushed), so
// the processor overlaps consecutive nodes' loads and box tests: with the AVX version below,
// `peer_compare --ab 8`, 1 / 2 threads, torus100k -> 1m 1.058 / 1.078, torus1m -> torus100k
// 1.022 / 1.025, against the AVX version depth first (docs/performance-log.md §3). Which order the
// blocks come in changes no answer: a packet tests every face whose bound is within its cutoff,
// and keep_ties orders ties by face.
std::size_t gather_leaf_blocks(const WideNode* nodes, std::uint32_t root, const float lo[3],
                               const float hi[3], float limit2, std::size_t max_blocks,
                               std::uint32_t* queue, std::size_t queue_size, GatheredBlocks out);
// The same, element for element, with AVX lane permutations packing a node's kept children (one
// per row: six box rows, the block indices, the queue) where the baseline writes each child's
// entries one by one. Precondition: the CPU runs AVX2 (simd_level() != kBaseline); only in
// builds with MESHDEV_X86_KERNELS.
std::size_t gather_leaf_blocks_avx2(const WideNode* nodes, std::uint32_t root, const float lo[3],
                                    const float hi[3], float limit2, std::size_t max_blocks,
                                    std::uint32_t* queue, std::size_t queue_size,
                                    GatheredBlocks out);

// A query's share of a packet's gathered blocks: the indices i < count of the blocks whose boxes
// lo[axis][i], hi[axis][i] lie within squared distance `limit2` of point q (box_gap2's arithmetic
// with the box [q, q], as the walk above; kept unless gap2 > limit2, so NaN gaps are kept),
// written as bytes to `which` in increasing order. Returns how many. Each row is 16-byte aligned
// with count rounded up to a multiple of 8 readable entries (those past count are read and never
// kept); `which` needs room for count + 8 (entries are written 4 or 8 at a time past the last
// kept). Preconditions: count <= 256. O(count).
std::size_t blocks_near_point(const float* const lo[3], const float* const hi[3], std::size_t count,
                              const float q[3], float limit2, std::uint8_t* which);
// The same, eight blocks per step in AVX lanes where the baseline takes four. Precondition: the
// CPU runs AVX2 (simd_level() != kBaseline); only in builds with MESHDEV_X86_KERNELS.
std::size_t blocks_near_point_avx2(const float* const lo[3], const float* const hi[3],
                                   std::size_t count, const float q[3], float limit2,
                                   std::uint8_t* which);

}  // namespace meshdev::detail
