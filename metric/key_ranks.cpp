#include "metric/key_ranks.h"

#include <cassert>

namespace meshdev::detail {

void key_ranks(const std::uint64_t* key, std::uint32_t count, std::uint32_t* rank) {
  assert(count <= kMaxRankKeys);
  for (std::uint32_t i = 0; i < count; ++i) {
    std::uint32_t r = 0;
    for (std::uint32_t j = 0; j < count; ++j) r += key[j] < key[i];
    rank[i] = r;
  }
}

#if !defined(MESHDEV_X86_KERNELS)
void key_ranks_avx2(const std::uint64_t*, std::uint32_t, std::uint32_t*) {
  assert(false && "no AVX2 kernels in this build");
}
#endif

}  // namespace meshdev::detail
