// key_ranks_avx2: key_ranks with four 64-bit comparisons per instruction. This translation unit
// alone is compiled with -mavx2 (metric/CMakeLists.txt) and is entered only after the caller
// checked the CPU (simd_level()), so it uses intrinsics and plain code only: no inline function
// shared with other translation units, whose AVX2 copy the linker could pick for everyone.
#include <immintrin.h>

#include <cassert>

#include "metric/key_ranks.h"

namespace meshdev::detail {

// AVX2 compares 64-bit lanes as signed integers: with the top bit of every key flipped, signed
// order is the keys' unsigned order. Padding lanes hold the largest signed value, which no key's
// flipped value exceeds, so they count for none.
void key_ranks_avx2(const std::uint64_t* key, std::uint32_t count, std::uint32_t* rank) {
  assert(count <= kMaxRankKeys);
  constexpr std::uint64_t kTop = std::uint64_t{1} << 63;
  alignas(32) std::uint64_t flipped[kMaxRankKeys];
  const std::uint32_t padded = (count + 3) / 4 * 4;
  for (std::uint32_t i = 0; i < count; ++i) flipped[i] = key[i] ^ kTop;
  for (std::uint32_t i = count; i < padded; ++i) flipped[i] = kTop - 1;
  for (std::uint32_t i = 0; i < count; ++i) {
    const __m256i x = _mm256_set1_epi64x(static_cast<long long>(flipped[i]));
    __m256i below = _mm256_setzero_si256();  // minus the count of smaller keys, per lane
    for (std::uint32_t j = 0; j < padded; j += 4) {
      const __m256i y = _mm256_load_si256(reinterpret_cast<const __m256i*>(flipped + j));
      below = _mm256_add_epi64(below, _mm256_cmpgt_epi64(x, y));  // -1 where y < x
    }
    const __m128i half =
        _mm_add_epi64(_mm256_castsi256_si128(below), _mm256_extracti128_si256(below, 1));
    const __m128i sum = _mm_add_epi64(half, _mm_unpackhi_epi64(half, half));
    rank[i] = static_cast<std::uint32_t>(-_mm_cvtsi128_si64(sum));
  }
}

}  // namespace meshdev::detail
