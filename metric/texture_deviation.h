#pragma once
// Cohen's texture deviation (Cohen, Olano, Manocha 1998; the paper's §2.3, Eq. 2):
//   T(p, S_b) = | p - F_b^-1(F_a(p)) |,
// the distance from p on mesh A to the point p'' of mesh B that has the same texture coordinates
// (u, v) = F_a(p). It is not a nearest-point measure: p'' comes from B's parameterisation, found
// with a UvIndex over B's UV triangles.
//
// F_b^-1 is a function only where B's UV triangles do not overlap. meshdev decides:
//  - several faces of B contain (u, v) at 3D points farther apart than `same_point` (overlapping
//    or mirrored charts): T is the smallest of the distances (the paper's §3.1 minimum rule) and
//    the sample is counted as `multiple`;
//  - no face of B contains (u, v) (the UV lies in a gap between B's charts, e.g. after a
//    simplification moved a chart boundary): p'' is the point of B whose UV is nearest to (u, v),
//    and the sample is counted as `outside` with that UV gap. Nothing is dropped.
#include <array>
#include <cstdint>

#include "metric/mesh.h"
#include "metric/uv_index.h"

namespace meshdev {

enum class CohenCase : std::uint8_t {
  kUnique,    // exactly one point of B has the UV (or several coincide in 3D)
  kMultiple,  // several distinct points of B have the UV: the smallest distance is reported
  kOutside,   // no point of B has the UV: the UV-nearest point of B is used
};

struct CohenResult {
  double distance = 0;  // |p - p''|, mesh units
  Vec3 point;           // p''
  std::uint32_t face = 0;
  std::array<double, 3> bary{1, 0, 0};
  CohenCase kind = CohenCase::kUnique;
  double uv_gap = 0;  // UV distance from (u, v) to B's UV triangles (kOutside only)
};

// T(p, S_b) for p with texture coordinates (u, v); `index` is over `b` and its texcoord.
// `same_point`: 3D distance below which two points of B count as one (pass ~1e-9 x diag(B)).
// `scratch` is reused between calls. O(faces in one UV cell), more when outside.
CohenResult cohen_texture_deviation(const Vec3& p, double u, double v, const TriMesh& b,
                                    const UvIndex& index, double same_point,
                                    std::vector<UvHit>& scratch);

}  // namespace meshdev
