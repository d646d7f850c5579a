#include "metric/vertex_normals.h"

#include <algorithm>
#include <cmath>

namespace meshdev {

Vec3 face_normal(const TriMesh& mesh, std::size_t f) {
  const Triangle& t = mesh.faces[f];
  const Vec3 n = cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                       mesh.positions[t[2]] - mesh.positions[t[0]]);
  const double len = norm(n);
  return len > 0.0 ? (1.0 / len) * n : Vec3{};
}

std::vector<Vec3> compute_vertex_normals(const TriMesh& mesh, NormalWeighting weighting) {
  std::vector<Vec3> sum(mesh.positions.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Triangle& t = mesh.faces[f];
    const Vec3 n = face_normal(mesh, f);
    if (n == Vec3{}) continue;
    for (int c = 0; c < 3; ++c) {
      double w = 1.0;
      if (weighting == NormalWeighting::kArea) {
        w = face_area(mesh, f);
      } else if (weighting == NormalWeighting::kAngle) {
        const Vec3& p = mesh.positions[t[c]];
        const Vec3 e1 = mesh.positions[t[(c + 1) % 3]] - p;
        const Vec3 e2 = mesh.positions[t[(c + 2) % 3]] - p;
        w = std::atan2(norm(cross(e1, e2)), dot(e1, e2));
      }
      sum[t[c]] = sum[t[c]] + w * n;
    }
  }
  for (Vec3& n : sum) {
    const double len = norm(n);
    n = len > 0.0 ? (1.0 / len) * n : Vec3{};
  }
  return sum;
}

}  // namespace meshdev
