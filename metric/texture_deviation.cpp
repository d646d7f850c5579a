#include "metric/texture_deviation.h"

namespace meshdev {
namespace {

Vec3 point_at(const TriMesh& b, std::uint32_t f, const std::array<double, 3>& w) {
  const Triangle& t = b.faces[f];
  return w[0] * b.positions[t[0]] + w[1] * b.positions[t[1]] + w[2] * b.positions[t[2]];
}

}  // namespace

CohenResult cohen_texture_deviation(const Vec3& p, double u, double v, const TriMesh& b,
                                    const UvIndex& index, double same_point,
                                    std::vector<UvHit>& hits) {
  CohenResult r;
  index.containing(u, v, hits);
  if (hits.empty()) {
    // No point of B has this UV: take the UV-nearest one and say so.
    const UvHit h = index.nearest(u, v);
    r.face = h.face;
    r.bary = h.bary;
    r.point = point_at(b, h.face, h.bary);
    r.distance = norm(p - r.point);
    r.kind = CohenCase::kOutside;
    r.uv_gap = h.uv_distance;
    return r;
  }
  bool first = true;
  Vec3 first_point;
  for (const UvHit& h : hits) {
    const Vec3 q = point_at(b, h.face, h.bary);
    const double d = norm(p - q);
    if (first) {
      first_point = q;
      r = {d, q, h.face, h.bary, CohenCase::kUnique, 0.0};
      first = false;
      continue;
    }
    if (norm(q - first_point) > same_point) r.kind = CohenCase::kMultiple;
    if (d < r.distance) {
      r.distance = d;
      r.point = q;
      r.face = h.face;
      r.bary = h.bary;
    }
  }
  return r;
}

}  // namespace meshdev
