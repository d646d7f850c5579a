// face_interior_x4 for AVX2 (no FMA): this translation unit alone is compiled with -mavx2
// (metric/CMakeLists.txt) and is entered only after the CPU check (simd_level()). It calls no
// inline function shared with other translation units (the linker could pick its AVX2 copy for
// everyone), so the feature rule of make_hit (closest_point_triangle.h) is written out below.
#include <immintrin.h>

#include "metric/face_interior_x4.h"

#include <cstddef>

namespace meshdev::detail {

// The stores below write sq_distance and the barycentrics as one vector.
static_assert(offsetof(SurfaceHit, bary) == offsetof(SurfaceHit, sq_distance) + 8 &&
                  offsetof(SurfaceHit, point) == offsetof(SurfaceHit, bary) + 24,
              "SurfaceHit: sq_distance, bary and point are consecutive doubles");

namespace {

struct V4 {
  __m256d x, y, z;
};

// The four points' coordinates by axis, lane l from *v[l].
V4 load4(const Vec3* const v[4]) {
  const __m256d t0 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&v[0]->x)),
                                          _mm_loadu_pd(&v[2]->x), 1);  // x0 y0 x2 y2
  const __m256d t1 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&v[1]->x)),
                                          _mm_loadu_pd(&v[3]->x), 1);  // x1 y1 x3 y3
  return {_mm256_unpacklo_pd(t0, t1), _mm256_unpackhi_pd(t0, t1),
          _mm256_setr_pd(v[0]->z, v[1]->z, v[2]->z, v[3]->z)};
}

V4 sub(const V4& a, const V4& b) {
  return {_mm256_sub_pd(a.x, b.x), _mm256_sub_pd(a.y, b.y), _mm256_sub_pd(a.z, b.z)};
}
// a.x * b.x + a.y * b.y + a.z * b.z, in that order (dot in metric/vec3.h)
__m256d dot(const V4& a, const V4& b) {
  return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a.x, b.x), _mm256_mul_pd(a.y, b.y)),
                       _mm256_mul_pd(a.z, b.z));
}
__m256d le(__m256d a, __m256d b) {
  return _mm256_cmp_pd(a, b, _CMP_LE_OQ);
}
__m256d ge(__m256d a, __m256d b) {
  return _mm256_cmp_pd(a, b, _CMP_GE_OQ);
}
__m256d gt(__m256d a, __m256d b) {
  return _mm256_cmp_pd(a, b, _CMP_GT_OQ);
}
__m256d eq(__m256d a, __m256d b) {
  return _mm256_cmp_pd(a, b, _CMP_EQ_OQ);
}
__m256d both(__m256d a, __m256d b) {
  return _mm256_and_pd(a, b);
}
__m256d either(__m256d a, __m256d b) {
  return _mm256_or_pd(a, b);
}
// The walk's test of edge AB's region from vc, d1, d3 (and of AC's from vb, d2, d6): v <= 0,
// s >= 0, t <= 0 and s - t > 0.
__m256d edge_region(__m256d v, __m256d s, __m256d t) {
  const __m256d zero = _mm256_setzero_pd();
  return both(both(le(v, zero), ge(s, zero)), both(le(t, zero), gt(_mm256_sub_pd(s, t), zero)));
}

}  // namespace

unsigned face_interior_x4(const Vec3* const p4[4], const Vec3* const a4[4], const Vec3* const b4[4],
                          const Vec3* const c4[4], SurfaceHit* const out[4]) {
  const V4 p = load4(p4), a = load4(a4), b = load4(b4), c = load4(c4);
  const __m256d zero = _mm256_setzero_pd();
  // triangle_frame
  const V4 ab = sub(b, a), ac = sub(c, a);
  const __m256d ab2 = dot(ab, ab), ac2 = dot(ac, ac);
  const V4 n = {_mm256_sub_pd(_mm256_mul_pd(ab.y, ac.z), _mm256_mul_pd(ab.z, ac.y)),
                _mm256_sub_pd(_mm256_mul_pd(ab.z, ac.x), _mm256_mul_pd(ab.x, ac.z)),
                _mm256_sub_pd(_mm256_mul_pd(ab.x, ac.y), _mm256_mul_pd(ab.y, ac.x))};
  const __m256d n2 = dot(n, n);
  const V4 bc = sub(c, b);
  __m256d other = either(either(eq(ab2, zero), eq(ac2, zero)), eq(dot(bc, bc), zero));
  other =
      either(other, _mm256_cmp_pd(n2, _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(1e-12), ab2), ac2),
                                  _CMP_NGT_UQ));  // degenerate: !(n2 > 1e-12 ab2 ac2)
  // The Voronoi walk's tests (closest_point_on_triangle), every one: a lane in none of the vertex
  // and edge regions is in the face's.
  const V4 ap = sub(p, a);
  const __m256d d1 = dot(ab, ap), d2 = dot(ac, ap);
  other = either(other, both(le(d1, zero), le(d2, zero)));
  const V4 bp = sub(p, b);
  const __m256d d3 = dot(ab, bp), d4 = dot(ac, bp);
  other = either(other, both(ge(d3, zero), le(d4, d3)));
  const __m256d vc = _mm256_sub_pd(_mm256_mul_pd(d1, d4), _mm256_mul_pd(d3, d2));
  other = either(other, edge_region(vc, d1, d3));
  const V4 cp = sub(p, c);
  const __m256d d5 = dot(ab, cp), d6 = dot(ac, cp);
  other = either(other, both(ge(d6, zero), le(d5, d6)));
  const __m256d vb = _mm256_sub_pd(_mm256_mul_pd(d5, d2), _mm256_mul_pd(d1, d6));
  other = either(other, edge_region(vb, d2, d6));
  const __m256d va = _mm256_sub_pd(_mm256_mul_pd(d3, d6), _mm256_mul_pd(d5, d4));
  const __m256d e43 = _mm256_sub_pd(d4, d3), e56 = _mm256_sub_pd(d5, d6);
  other = either(other, both(both(le(va, zero), ge(e43, zero)),
                             both(ge(e56, zero), gt(_mm256_add_pd(e43, e56), zero))));
  const __m256d sum = _mm256_add_pd(_mm256_add_pd(va, vb), vc);
  other = either(other, _mm256_cmp_pd(sum, zero, _CMP_NGT_UQ));  // !(va + vb + vc > 0)
  const unsigned face = ~static_cast<unsigned>(_mm256_movemask_pd(other)) & 0xfu;
  if (face == 0) return 0;
  // The face region.
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d denom = _mm256_div_pd(one, sum);
  const __m256d v = _mm256_mul_pd(vb, denom), w = _mm256_mul_pd(vc, denom);
  const __m256d h = dot(ap, n);
  const __m256d sq = _mm256_div_pd(_mm256_mul_pd(h, h), n2);
  const __m256d u = _mm256_sub_pd(_mm256_sub_pd(one, v), w);
  const V4 q = {_mm256_add_pd(_mm256_add_pd(a.x, _mm256_mul_pd(v, ab.x)), _mm256_mul_pd(w, ac.x)),
                _mm256_add_pd(_mm256_add_pd(a.y, _mm256_mul_pd(v, ab.y)), _mm256_mul_pd(w, ac.y)),
                _mm256_add_pd(_mm256_add_pd(a.z, _mm256_mul_pd(v, ab.z)), _mm256_mul_pd(w, ac.z))};
  // Lane by lane into the hits: (sq, u, v, w) and (x, y, z) transposed.
  const __m256d s0 = _mm256_unpacklo_pd(sq, u), s1 = _mm256_unpackhi_pd(sq, u);  // sq0 u0 sq2 u2
  const __m256d s2 = _mm256_unpacklo_pd(v, w), s3 = _mm256_unpackhi_pd(v, w);    // v0 w0 v2 w2
  const __m256d r0 = _mm256_unpacklo_pd(q.x, q.y), r1 = _mm256_unpackhi_pd(q.x, q.y);
  const __m256d lanes_sq[4] = {
      _mm256_permute2f128_pd(s0, s2, 0x20), _mm256_permute2f128_pd(s1, s3, 0x20),
      _mm256_permute2f128_pd(s0, s2, 0x31), _mm256_permute2f128_pd(s1, s3, 0x31)};
  const __m128d lanes_xy[4] = {_mm256_castpd256_pd128(r0), _mm256_castpd256_pd128(r1),
                               _mm256_extractf128_pd(r0, 1), _mm256_extractf128_pd(r1, 1)};
  alignas(32) double z[4];
  _mm256_store_pd(z, q.z);
  // Features (closest_point_triangle.h, make_hit): a vertex where two barycentrics are 0, an edge
  // where one is.
  const unsigned zu = static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(u, zero, _CMP_EQ_OQ)));
  const unsigned zv = static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(v, zero, _CMP_EQ_OQ)));
  const unsigned zw = static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(w, zero, _CMP_EQ_OQ)));
  for (int l = 0; l < 4; ++l) {
    SurfaceHit& s = *out[l];
    _mm256_storeu_pd(&s.sq_distance, lanes_sq[l]);  // sq_distance, bary[0..2]
    _mm_storeu_pd(&s.point.x, lanes_xy[l]);
    s.point.z = z[l];
    const unsigned zeros = (zu >> l & 1u) + (zv >> l & 1u) + (zw >> l & 1u);
    s.feature = zeros >= 2 ? Feature::kVertex : (zeros == 1 ? Feature::kEdge : Feature::kFace);
  }
  return face;
}

}  // namespace meshdev::detail
