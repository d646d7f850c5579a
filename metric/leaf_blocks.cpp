#include "metric/leaf_blocks.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "metric/float_rounding.h"
#include "metric/mesh.h"
#include "metric/vec3.h"

namespace meshdev::detail {
namespace {

// The conditioning kappa = |ab||ac| / |ab x ac| of a triangle with edges ab, ac (float frame), or
// +inf where the triangle bound must never cull it: |ab x ac|^2 near float underflow
// (kMinCullNormal2) or a sliver (kappa > kMaxCullKappa). The packets' planes
// (PlaneKernels::block_planes) test the same limits on squares.
double cull_kappa(const Vec3& ab, const Vec3& ac) {
  const double n2 = squared_norm(cross(ab, ac));
  if (!(n2 >= kMinCullNormal2)) return std::numeric_limits<double>::infinity();
  const double kappa = norm(ab) * norm(ac) / std::sqrt(n2);
  return kappa <= kMaxCullKappa ? kappa : std::numeric_limits<double>::infinity();  // NaN too
}

}  // namespace

LeafBlockSums fill_leaf_block(const double* positions, const std::uint32_t* corners,
                              const std::uint32_t* face_ids, std::uint32_t count,
                              const FrameMap& frame, LeafBlock& out) {
  assert(count >= 1 && count <= 4);
  constexpr float kInf = std::numeric_limits<float>::infinity();
  LeafBlockSums sums;
  for (int lane = 0; lane < 4; ++lane) {
    out.margin[lane] = kInf;
    out.face[lane] = kNoFace;
    for (int corner = 0; corner < 3; ++corner)
      for (int k = 0; k < 3; ++k) out.corner[corner][k][lane] = 0.0f;
  }
  for (std::uint32_t lane = 0; lane < count; ++lane) {
    const std::uint32_t f = face_ids[lane];
    out.face[lane] = f;
    double c[3][3];  // the float corners, exactly, in double
    for (int corner = 0; corner < 3; ++corner) {
      const double* p = positions + 3 * std::size_t{corners[3 * std::size_t{f} + corner]};
      double err2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double x = (p[k] - frame.origin[k]) * frame.scale;
        const float r = static_cast<float>(x);
        out.corner[corner][k][lane] = r;
        c[corner][k] = r;
        err2 += (c[corner][k] - x) * (c[corner][k] - x);
      }
      sums.corner_error2 = std::max(sums.corner_error2, err2);
    }
    const Vec3 a{c[0][0], c[0][1], c[0][2]}, b{c[1][0], c[1][1], c[1][2]},
        cc{c[2][0], c[2][1], c[2][2]};
    const Vec3 ab = b - a, ac = cc - a;
    sums.edge_sum +=
        std::sqrt(std::max({squared_norm(ab), squared_norm(ac), squared_norm(cc - b)}));
    const double kappa = cull_kappa(ab, ac);
    if (std::isfinite(kappa))
      out.margin[lane] = round_up_to_float(kMarginConstant * kFloatUnit * (2.0 + kappa));
  }
  return sums;
}

#if !defined(MESHDEV_X86_KERNELS)
LeafBlockSums fill_leaf_block_avx2(const double*, const std::uint32_t*, const std::uint32_t*,
                                   std::uint32_t, const FrameMap&, LeafBlock&) {
  assert(false && "no AVX2 kernels in this build");
  return {};
}
#endif

}  // namespace meshdev::detail
