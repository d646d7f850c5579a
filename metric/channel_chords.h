#pragma once
// The per-vertex channel comparisons of the deviation loop's inline path (metric/
// attribute_deviation.cpp) for four samples at once, in the four double lanes of AVX registers.
// Each lane performs exactly the operations of the one-sample path in their order (barycentric_mix,
// unit_normal, the chords of unit_normal_distance, the raw Euclidean distance), and IEEE add,
// subtract, multiply, divide and square root are correctly rounded at any width, so each lane's
// result is bit for bit the one-sample result. Compiled for AVX2 in its own translation unit
// (without FMA, and the library's -ffp-contract=off: no fused multiply-add may change a rounding)
// and entered only where simd_level() (metric/plane_bounds.h) is not kBaseline.
#include <cstddef>
#include <cstdint>

namespace meshdev::detail {

// One sample of the inline path as plain data: the corners (vertex indices) and barycentrics of
// its face on the reference and of its one tie's face on the target.
struct ChordSample {
  const std::uint32_t* ta;
  const double* bary_a;
  const std::uint32_t* tb;
  const double* bary_b;
};

// What channel_chords_x4 gives for one channel, lane l for sample l.
struct ChannelChords {
  // Unit normals: |na - nb| of the unit normals (unit_normal) of the interpolated values (the zero
  // vector where the length is 0 or NaN, as unit_normal); raw values: their Euclidean distance.
  double chord[4];
  double across[4];  // unit normals: |na + nb|; raw values: unset
  int either_zero;   // unit normals: bit l set where lane l's na or nb is the zero vector
};

// A per-vertex channel of the inline path: `dim` doubles per vertex on each mesh, compared as
// unit normals (dim 3) or as raw values by Euclidean distance.
struct ChordChannel {
  const double* reference;
  const double* target;
  int dim;
  bool unit_normals;
};

// The comparisons of `count` per-vertex channels for four samples, out[j] for channels[j];
// channels of raw values of more than 3 components are left to the caller (out[j] unset). The
// barycentrics are laid into lanes once for all channels. Absolute units of each channel.
// Preconditions: the vertex indices within the arrays, the CPU runs AVX2 (simd_level() !=
// kBaseline). O(sum of dims).
void channel_chords_x4(const ChordChannel* channels, std::size_t count, const ChordSample s[4],
                       ChannelChords* out);

}  // namespace meshdev::detail
