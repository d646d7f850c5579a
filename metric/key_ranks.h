#pragma once
// The rank of each of up to kMaxRankKeys distinct 64-bit keys (how many of the keys are
// smaller): the sort of the BVH build's small subtrees (TriangleBvh::build), which moves each face
// straight to its rank. All count x count comparisons, without a branch on the keys: the keys
// come in no order a branch predictor learns. Two versions with the same output: the baseline
// (metric/key_ranks.cpp: one comparison at a time, as x86-64's base instruction set has no 64-bit
// vector comparison) and an AVX2 version (metric/key_ranks_avx2.cpp, its own translation unit
// compiled with -mavx2, entered only where simd_level() is not kBaseline: four comparisons per
// instruction).
#include <cstdint>

namespace meshdev::detail {

constexpr std::uint32_t kMaxRankKeys = 64;

// rank[i] = the number of j < count with key[j] < key[i] (unsigned order). With distinct keys the
// ranks are a permutation of 0 .. count - 1. Preconditions: count <= kMaxRankKeys. O(count^2).
void key_ranks(const std::uint64_t* key, std::uint32_t count, std::uint32_t* rank);
// The same, equal element for element. Precondition: the CPU runs AVX2 (simd_level() !=
// kBaseline); only in builds with MESHDEV_X86_KERNELS.
void key_ranks_avx2(const std::uint64_t* key, std::uint32_t count, std::uint32_t* rank);

}  // namespace meshdev::detail
