#include "metric/centre_bins.h"

#include <cassert>

namespace meshdev::detail {

void centre_bins(const FaceBox* boxes, std::uint32_t count, int axis, double lo, double scale,
                 int bin_count, std::uint8_t* bins) {
  assert(axis >= 0 && axis < 3 && bin_count >= 1 && bin_count <= 256);
  const int top = bin_count - 1;
  for (std::uint32_t i = 0; i < count; ++i) {
    float key = boxes[i].lo[axis] + boxes[i].hi[axis];
    if (!(key == key)) key = 0.0f;
    const double t = (key - lo) * scale;
    bins[i] = static_cast<std::uint8_t>(t >= top ? top : t > 0.0 ? static_cast<int>(t) : 0);
  }
}

#if !defined(MESHDEV_X86_KERNELS)
void centre_bins_avx2(const FaceBox*, std::uint32_t, int, double, double, int, std::uint8_t*) {
  assert(false && "no AVX2 kernels in this build");
}
#endif

}  // namespace meshdev::detail
