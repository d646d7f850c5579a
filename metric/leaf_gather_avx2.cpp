// gather_leaf_blocks_avx2: the packets' tree walk with each node's kept children packed by lane
// permutations. This translation unit alone is compiled with -mavx2 (metric/CMakeLists.txt) and is
// entered only after the caller checked the CPU (simd_level()), so it uses intrinsics and plain
// code only: no inline function shared with other translation units, whose AVX copy the linker
// could pick for everyone.
#include <immintrin.h>

#include <cassert>
#include <cstdint>
#include <cstring>

#include "metric/leaf_gather.h"

namespace meshdev::detail {
namespace {

// For each 4-bit mask, the lanes whose bit is set, in increasing order, then lane 0: the control
// of _mm_permutevar_ps that packs those lanes to the front.
alignas(16) constexpr std::int32_t kPack[16][4] = {
    {0, 0, 0, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}, {2, 0, 0, 0}, {0, 2, 0, 0},
    {1, 2, 0, 0}, {0, 1, 2, 0}, {3, 0, 0, 0}, {0, 3, 0, 0}, {1, 3, 0, 0}, {0, 1, 3, 0},
    {2, 3, 0, 0}, {0, 2, 3, 0}, {1, 2, 3, 0}, {0, 1, 2, 3}};
constexpr std::uint32_t kCount[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};

}  // namespace

// The same walk as gather_leaf_blocks (metric/leaf_gather.cpp), with the same arithmetic for the
// gaps (SSE's max, which returns its second operand where either is NaN; no fused multiply-add):
// the children kept are the same, and each of their entries is packed to the front of its row in
// lane order and stored at the count (or the queue's tail), as the baseline's writes one child at
// a time leave them.
std::size_t gather_leaf_blocks_avx2(const WideNode* nodes, std::uint32_t root, const float lo[3],
                                    const float hi[3], float limit2, std::size_t max_blocks,
                                    std::uint32_t* queue, std::size_t queue_size,
                                    GatheredBlocks out) {
  assert((root & kWideLeafBit) == 0);
  const __m128 qlo[3] = {_mm_set1_ps(lo[0]), _mm_set1_ps(lo[1]), _mm_set1_ps(lo[2])};
  const __m128 qhi[3] = {_mm_set1_ps(hi[0]), _mm_set1_ps(hi[1]), _mm_set1_ps(hi[2])};
  const __m128 limit = _mm_set1_ps(limit2);
  const __m128 zero = _mm_setzero_ps();
  const __m128i empty = _mm_set1_epi32(-1);
  const __m128i index_bits = _mm_set1_epi32(static_cast<int>(~kWideLeafBit));
  std::size_t head = 0, tail = 0;  // the next node to open; the queue's end
  std::size_t count = 0;           // blocks kept; a node writes four entries from there
  queue[tail++] = root;
  while (head < tail) {
    const WideNode& node = nodes[queue[head++]];
    __m128 blo[3], bhi[3];
    __m128 d2 = zero;
    for (int a = 0; a < 3; ++a) {
      blo[a] = _mm_load_ps(node.lo[a]);
      bhi[a] = _mm_load_ps(node.hi[a]);
      const __m128 d =
          _mm_max_ps(_mm_max_ps(_mm_sub_ps(blo[a], qhi[a]), _mm_sub_ps(qlo[a], bhi[a])), zero);
      d2 = _mm_add_ps(d2, _mm_mul_ps(d, d));
    }
    const __m128i refs = _mm_load_si128(reinterpret_cast<const __m128i*>(node.child));
    const unsigned keep =
        ~static_cast<unsigned>(_mm_movemask_ps(_mm_cmpgt_ps(d2, limit))) &
        ~static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(refs, empty)))) &
        0xfu;
    const auto leaf_bits = static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(refs)));
    const unsigned inner = keep & ~leaf_bits, leaves = keep & leaf_bits;
    const __m128i pack_inner = _mm_load_si128(reinterpret_cast<const __m128i*>(kPack[inner]));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(queue + tail),
                     _mm_castps_si128(_mm_permutevar_ps(_mm_castsi128_ps(refs), pack_inner)));
    tail += kCount[inner];
    const __m128i pack = _mm_load_si128(reinterpret_cast<const __m128i*>(kPack[leaves]));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out.block + count),
                     _mm_castps_si128(_mm_permutevar_ps(
                         _mm_castsi128_ps(_mm_and_si128(refs, index_bits)), pack)));
    for (int a = 0; a < 3; ++a) {
      _mm_storeu_ps(out.lo[a] + count, _mm_permutevar_ps(blo[a], pack));
      _mm_storeu_ps(out.hi[a] + count, _mm_permutevar_ps(bhi[a], pack));
    }
    count += kCount[leaves];
    if (count > max_blocks || tail > queue_size) return max_blocks + 1;
  }
  return count;
}

namespace {

// For a mask of eight lanes: the kept lanes' numbers packed as bytes, lowest first.
struct PackedLanes8 {
  std::uint64_t lanes[256];
  constexpr PackedLanes8() : lanes() {
    for (unsigned mask = 0; mask < 256; ++mask) {
      int n = 0;
      for (unsigned lane = 0; lane < 8; ++lane)
        if ((mask >> lane & 1u) != 0) lanes[mask] |= std::uint64_t{lane} << (8 * n++);
    }
  }
};
constexpr PackedLanes8 kPackedLanes8;

}  // namespace

// blocks_near_point's gaps in eight lanes: the same operations in the same order (SSE's max, no
// fused multiply-add; the sum of squares starts from its first term, as 0 + x = x for the squares,
// which are >= 0 or NaN), so the same blocks are kept. Against four lanes, with the packet's
// frame in SSE2 lanes (metric/query_frame.h), `peer_compare A B 1000000 --ab 8`, 1 / 2 threads:
// torus100k -> 1m 1.050 / 1.033, torus100k -> 10k 1.045 / 1.039, torus1m -> 100k 1.039 / 1.029,
// buildings_s40k -> buildings 1.040 / 1.043, armadillo 1.033 / 1.034; this part alone 1.028 /
// 1.035 on torus100k -> 1m (docs/performance-log.md §3, forty-sixth session).
std::size_t blocks_near_point_avx2(const float* const lo[3], const float* const hi[3],
                                   std::size_t count, const float q[3], float limit2,
                                   std::uint8_t* which) {
  assert(count <= 256);
  const __m256 p[3] = {_mm256_set1_ps(q[0]), _mm256_set1_ps(q[1]), _mm256_set1_ps(q[2])};
  const __m256 limit = _mm256_set1_ps(limit2);
  const __m256 zero = _mm256_setzero_ps();
  const float* const l[3] = {lo[0], lo[1], lo[2]};  // not reloaded after the stores to `which`
  const float* const h[3] = {hi[0], hi[1], hi[2]};
  std::size_t selected = 0;
  for (std::size_t b = 0; b < count; b += 8) {
    __m256 gap2 = zero;
    for (int a = 0; a < 3; ++a) {
      const __m256 gap =
          _mm256_max_ps(_mm256_max_ps(_mm256_sub_ps(_mm256_loadu_ps(l[a] + b), p[a]),
                                      _mm256_sub_ps(p[a], _mm256_loadu_ps(h[a] + b))),
                        zero);
      gap2 = a == 0 ? _mm256_mul_ps(gap, gap) : _mm256_add_ps(gap2, _mm256_mul_ps(gap, gap));
    }
    unsigned keep =
        static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(gap2, limit, _CMP_NGT_UQ)));
    if (count - b < 8) keep &= (1u << (count - b)) - 1u;  // past the count: never
    const std::uint64_t kept = kPackedLanes8.lanes[keep] + b * 0x0101010101010101ull;
    std::memcpy(which + selected, &kept, sizeof kept);
    selected += static_cast<std::size_t>(__builtin_popcount(keep));
  }
  return selected;
}

}  // namespace meshdev::detail
