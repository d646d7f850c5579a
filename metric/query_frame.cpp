#include "metric/query_frame.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace meshdev::detail {

bool frame_query(const Vec3& p, const FrameMap& frame, double corner_error, float qf[3],
                 double& slack) {
  double q[3];
  for (int k = 0; k < 3; ++k) {
    q[k] = (p[k] - frame.origin[k]) * frame.scale;
    qf[k] = static_cast<float>(q[k]);
  }
  const bool cull = std::fabs(q[0]) < kMaxFrameQuery && std::fabs(q[1]) < kMaxFrameQuery &&
                    std::fabs(q[2]) < kMaxFrameQuery;  // false for NaN
  slack = corner_error;
  if (cull) {
    const double ex = qf[0] - q[0], ey = qf[1] - q[1], ez = qf[2] - q[2];
    slack += std::fabs(ex) + std::fabs(ey) + std::fabs(ez) +  // >= the rounding's length
             4e-16 * (std::fabs(q[0]) + std::fabs(q[1]) + std::fabs(q[2]) + 3.0);
  }
  return cull;
}

std::size_t frame_packet_scalar(const Vec3* points, std::size_t count, const FrameMap& frame,
                                double corner_error, const PacketExtent& extent, float (*qf)[3],
                                double* slack, float lo[3], float hi[3]) {
  assert(count >= 1);
  std::size_t k = 0;
  for (; k < count; ++k) {
    if (!frame_query(points[k], frame, corner_error, qf[k], slack[k])) break;
    float nlo[3], nhi[3];
    double diag2 = 0.0;
    for (int a = 0; a < 3; ++a) {
      const float q = qf[k][a];
      nlo[a] = k == 0 ? q : std::min(lo[a], q);
      nhi[a] = k == 0 ? q : std::max(hi[a], q);
      diag2 += (static_cast<double>(nhi[a]) - nlo[a]) * (static_cast<double>(nhi[a]) - nlo[a]);
    }
    if (diag2 > extent.max_diag2 || (k >= extent.full_from && diag2 > extent.full_diag2)) break;
    std::copy(nlo, nlo + 3, lo);
    std::copy(nhi, nhi + 3, hi);
  }
  return k;
}

#if defined(__SSE2__)
// frame_query's and frame_packet_scalar's operations in their order, x and y in the two lanes of
// one register and z in the low lane of another, without a branch per axis: the queries' box
// starts empty (+inf, -inf), so the first query's min and max are its own coordinates, and a sum
// that starts from 0 starts from its first term (the squares are >= 0 or NaN). About 60 fewer
// instructions per query (callgrind, torus100k -> 1m: to_frame's 67 and find_batch's own 90
// before, frame_packet's 82 and find_batch's 14 after); with the block selection in AVX2 lanes
// (metric/leaf_gather.h), `peer_compare A B 1000000 --ab 8`, 1 / 2 threads: torus100k -> 1m
// 1.050 / 1.033, the other pairs 1.029-1.045 (docs/performance-log.md §3, forty-sixth session);
// alone, torus100k -> 1m 1.016 / 1.012.
std::size_t frame_packet(const Vec3* points, std::size_t count, const FrameMap& frame,
                         double corner_error, const PacketExtent& extent, float (*qf)[3],
                         double* slack, float lo[3], float hi[3]) {
  assert(count >= 1);
  const __m128d origin_xy = _mm_set_pd(frame.origin[1], frame.origin[0]);
  const __m128d origin_z = _mm_set_sd(frame.origin[2]);
  const __m128d scale = _mm_set1_pd(frame.scale);
  const __m128d magnitude = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
  const __m128d max_query = _mm_set1_pd(kMaxFrameQuery);
  const float inf = std::numeric_limits<float>::infinity();
  __m128 box_lo = _mm_set1_ps(inf), box_hi = _mm_set1_ps(-inf);
  std::size_t k = 0;
  for (; k < count; ++k) {
    const double* p = &points[k].x;
    const __m128d q_xy = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(p), origin_xy), scale);
    const __m128d q_z = _mm_mul_sd(_mm_sub_sd(_mm_load_sd(p + 2), origin_z), scale);
    const __m128d abs_xy = _mm_and_pd(q_xy, magnitude), abs_z = _mm_and_pd(q_z, magnitude);
    const __m128d within = _mm_and_pd(_mm_cmplt_pd(abs_xy, max_query),
                                      _mm_cmplt_pd(_mm_unpacklo_pd(abs_z, abs_z), max_query));
    if (_mm_movemask_pd(within) != 3) break;  // NaN, or too far out to cull
    const __m128 f_xy = _mm_cvtpd_ps(q_xy);
    const __m128 f_z = _mm_cvtsd_ss(_mm_setzero_ps(), q_z);
    const __m128 f = _mm_movelh_ps(f_xy, f_z);
    _mm_storel_pi(reinterpret_cast<__m64*>(qf[k]), f);
    _mm_store_ss(qf[k] + 2, f_z);
    // Lanes (|e_x|, |q_x|) + (|e_y|, |q_y|), then + (|e_z|, |q_z|): the two sums of frame_query.
    const __m128d e_xy = _mm_and_pd(_mm_sub_pd(_mm_cvtps_pd(f_xy), q_xy), magnitude);
    const __m128d e_z = _mm_and_pd(_mm_sub_sd(_mm_cvtps_pd(f_z), q_z), magnitude);
    const __m128d sums =
        _mm_add_pd(_mm_add_pd(_mm_unpacklo_pd(e_xy, abs_xy), _mm_unpackhi_pd(e_xy, abs_xy)),
                   _mm_unpacklo_pd(e_z, abs_z));
    const double rounding = _mm_cvtsd_f64(sums),
                 length = _mm_cvtsd_f64(_mm_unpackhi_pd(sums, sums));
    slack[k] = corner_error + (rounding + 4e-16 * (length + 3.0));
    // The box with this query (min and max return their second operand on equal zeros, as
    // std::min(lo, q) and std::max(hi, q) do) and its squared diagonal.
    const __m128 next_lo = _mm_min_ps(f, box_lo), next_hi = _mm_max_ps(f, box_hi);
    const __m128d d_xy = _mm_sub_pd(_mm_cvtps_pd(next_hi), _mm_cvtps_pd(next_lo));
    const double d_z = _mm_cvtsd_f64(_mm_sub_sd(_mm_cvtps_pd(_mm_movehl_ps(next_hi, next_hi)),
                                                _mm_cvtps_pd(_mm_movehl_ps(next_lo, next_lo))));
    const __m128d sq_xy = _mm_mul_pd(d_xy, d_xy);
    const double diag2 =
        (_mm_cvtsd_f64(sq_xy) + _mm_cvtsd_f64(_mm_unpackhi_pd(sq_xy, sq_xy))) + d_z * d_z;
    if (diag2 > extent.max_diag2 || (k >= extent.full_from && diag2 > extent.full_diag2)) break;
    box_lo = next_lo;
    box_hi = next_hi;
  }
  if (k > 0) {
    alignas(16) float l[4], h[4];
    _mm_store_ps(l, box_lo);
    _mm_store_ps(h, box_hi);
    std::copy(l, l + 3, lo);
    std::copy(h, h + 3, hi);
  }
  return k;
}
#else
std::size_t frame_packet(const Vec3* points, std::size_t count, const FrameMap& frame,
                         double corner_error, const PacketExtent& extent, float (*qf)[3],
                         double* slack, float lo[3], float hi[3]) {
  return frame_packet_scalar(points, count, frame, corner_error, extent, qf, slack, lo, hi);
}
#endif

}  // namespace meshdev::detail
