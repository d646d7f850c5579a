#include "metric/leaf_gather.h"

#include <cassert>
#include <cstring>

#include "metric/simd4.h"

namespace meshdev::detail {

using simd::F4;

// Without a branch per child: each of a node's four children is written both to the queue and
// to the blocks, and counted where it is kept (inner nodes in the queue, leaf blocks in the
// list), as a loop over the kept children would leave them. The children kept vary from packet
// to packet, and such a loop branched on each (cachegrind's branch model: 1.8 M mispredictions
// there for 1 M queries of torus100k -> 1m, before 186b11d); chunk-interleaved, torus100k -> 1m
// +1.3-1.9 %, torus1m -> 100k +1.5 %, torus100k -> 10k +0.2-2.6 % (docs/performance-log.md §3).
std::size_t gather_leaf_blocks(const WideNode* nodes, std::uint32_t root, const float lo[3],
                               const float hi[3], float limit2, std::size_t max_blocks,
                               std::uint32_t* queue, std::size_t queue_size, GatheredBlocks out) {
  assert((root & kWideLeafBit) == 0);
  const F4 qlo[3] = {F4::splat(lo[0]), F4::splat(lo[1]), F4::splat(lo[2])};
  const F4 qhi[3] = {F4::splat(hi[0]), F4::splat(hi[1]), F4::splat(hi[2])};
  const F4 limit = F4::splat(limit2);
  std::size_t head = 0, tail = 0;  // the next node to open; the queue's end
  std::size_t count = 0;           // blocks kept; a node writes four entries from there
  queue[tail++] = root;
  while (head < tail) {
    const WideNode& node = nodes[queue[head++]];
    F4 blo[3], bhi[3];
    for (int a = 0; a < 3; ++a) {
      blo[a] = F4::load(node.lo[a]);
      bhi[a] = F4::load(node.hi[a]);
    }
    const unsigned keep =
        static_cast<unsigned>(~greater_mask(box_gap2(blo, bhi, qlo, qhi), limit)) & 0xfu;
    for (int k = 0; k < 4; ++k) {
      const std::uint32_t ref = node.child[k];
      const unsigned kept = (keep >> k & 1u) & static_cast<unsigned>(ref != kWideEmpty);
      const unsigned inner = static_cast<unsigned>((ref & kWideLeafBit) == 0);
      queue[tail] = ref;
      tail += kept & inner;
      out.block[count] = ref & ~kWideLeafBit;
      for (int a = 0; a < 3; ++a) {
        out.lo[a][count] = node.lo[a][k];
        out.hi[a][count] = node.hi[a][k];
      }
      count += kept & (inner ^ 1u);
    }
    if (count > max_blocks || tail > queue_size) return max_blocks + 1;
  }
  return count;
}

namespace {

// For a mask of four lanes: the kept lanes' numbers packed as bytes, lowest first, and how many.
constexpr std::uint32_t kPackedLanes[16] = {
    0x00000000, 0x00000000, 0x00000001, 0x00000100, 0x00000002, 0x00000200, 0x00000201, 0x00020100,
    0x00000003, 0x00000300, 0x00000301, 0x00030100, 0x00000302, 0x00030200, 0x00030201, 0x03020100};
constexpr std::uint32_t kLaneCount[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};

}  // namespace

// Without a branch per block: the kept lanes vary from query to query, and a loop over them
// branched on each (cachegrind's branch model: 1.9 M mispredictions for 1 M queries of
// torus100k -> 1m; +4.0-4.7 % when it went). Their indices are packed by a table and written in
// one store, four bytes (instructions per sample on torus100k -> 1m 2,019 -> 1,943 against a
// store per lane of the index and of its planes' address; docs/performance-log.md §3).
std::size_t blocks_near_point(const float* const lo[3], const float* const hi[3], std::size_t count,
                              const float q[3], float limit2, std::uint8_t* which) {
  assert(count <= 256);
  const F4 p[3] = {F4::splat(q[0]), F4::splat(q[1]), F4::splat(q[2])};
  const F4 limit = F4::splat(limit2);
  std::size_t selected = 0;
  for (std::size_t b = 0; b < count; b += 4) {
    F4 blo[3], bhi[3];
    for (int a = 0; a < 3; ++a) {
      blo[a] = F4::load(lo[a] + b);
      bhi[a] = F4::load(hi[a] + b);
    }
    unsigned keep = static_cast<unsigned>(~greater_mask(box_gap2(blo, bhi, p, p), limit)) & 0xfu;
    if (count - b < 4) keep &= (1u << (count - b)) - 1u;  // past the count: never
    const std::uint32_t kept = kPackedLanes[keep] + static_cast<std::uint32_t>(b) * 0x01010101u;
    std::memcpy(which + selected, &kept, sizeof kept);
    selected += kLaneCount[keep];
  }
  return selected;
}

#if !defined(MESHDEV_X86_KERNELS)
std::size_t gather_leaf_blocks_avx2(const WideNode*, std::uint32_t, const float[3], const float[3],
                                    float, std::size_t, std::uint32_t*, std::size_t,
                                    GatheredBlocks) {
  assert(false && "no AVX2 kernels in this build");
  return 0;
}
std::size_t blocks_near_point_avx2(const float* const[3], const float* const[3], std::size_t,
                                   const float[3], float, std::uint8_t*) {
  assert(false && "no AVX2 kernels in this build");
  return 0;
}
#endif

}  // namespace meshdev::detail
