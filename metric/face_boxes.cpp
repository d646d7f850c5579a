#include "metric/face_boxes.h"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstring>

#include "metric/float_rounding.h"
#include "metric/simd4.h"

namespace meshdev::detail {

void face_boxes(const double* positions, const std::uint32_t* corners, std::uint32_t begin,
                std::uint32_t end, const FrameMap& frame, FaceBox* out, LaneBounds& boxes,
                LaneBounds& centres, CornerBounds& corner_bounds) {
  using simd::F4;
  // The corners of the face kAhead on are prefetched: where faces are stored in no spatial order
  // their frame coordinates are cache misses (torus1m with its faces shuffled: the build 0.19 ->
  // 0.17 s; coherent meshes unchanged; docs/performance-log.md §3).
  constexpr std::uint32_t kAhead = 8;
  F4 box_lo = F4::load(boxes.lo), box_hi = F4::load(boxes.hi);
  F4 centre_lo = F4::load(centres.lo), centre_hi = F4::load(centres.hi);
  CornerBounds corner_box = corner_bounds;
  for (std::uint32_t f = begin; f < end; ++f) {
    if (f + kAhead < end)
      for (int corner = 0; corner < 3; ++corner)
        __builtin_prefetch(positions +
                           3 * std::size_t{corners[3 * std::size_t{f + kAhead} + corner]});
    double lo[3], hi[3];
    for (int corner = 0; corner < 3; ++corner) {
      const double* p = positions + 3 * std::size_t{corners[3 * std::size_t{f} + corner]};
      for (int k = 0; k < 3; ++k) {
        if (p[k] < corner_box.lo[k]) corner_box.lo[k] = p[k];
        if (p[k] > corner_box.hi[k]) corner_box.hi[k] = p[k];
        const double x = (p[k] - frame.origin[k]) * frame.scale;
        lo[k] = corner == 0 ? x : std::min(lo[k], x);
        hi[k] = corner == 0 ? x : std::max(hi[k], x);
      }
    }
    FaceBox& box = out[f - begin];
    for (int k = 0; k < 3; ++k) {
      box.lo[k] = round_down_to_float(lo[k]);
      box.hi[k] = round_up_to_float(hi[k]);
    }
    std::memcpy(&box.lo[3], &f, sizeof f);
    box.hi[3] = 0.0f;
    const F4 l = F4::load(box.lo), h = F4::load(box.hi), c = l + h;
    box_lo = simd::min(box_lo, l);
    box_hi = simd::max(box_hi, h);
    centre_lo = simd::min(centre_lo, c);
    centre_hi = simd::max(centre_hi, c);
  }
  simd::store(boxes.lo, box_lo);
  simd::store(boxes.hi, box_hi);
  simd::store(centres.lo, centre_lo);
  simd::store(centres.hi, centre_hi);
  corner_bounds = corner_box;
}

#if !defined(MESHDEV_X86_KERNELS)
void face_boxes_avx2(const double*, const std::uint32_t*, std::uint32_t, std::uint32_t,
                     const FrameMap&, FaceBox*, LaneBounds&, LaneBounds&, CornerBounds&) {
  assert(false && "no AVX2 kernels in this build");
}
#endif

}  // namespace meshdev::detail
