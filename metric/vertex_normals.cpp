#include "metric/vertex_normals.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace meshdev {

Vec3 face_normal(const TriMesh& mesh, std::size_t f) {
  const Triangle& t = mesh.faces[f];
  const Vec3 n = cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                       mesh.positions[t[2]] - mesh.positions[t[0]]);
  const double len = norm(n);
  return len > 0.0 ? (1.0 / len) * n : Vec3{};
}

namespace {

// The weight of face f's normal at its corner c.
double corner_weight(const TriMesh& mesh, std::size_t f, int c, NormalWeighting weighting) {
  if (weighting == NormalWeighting::kArea) return face_area(mesh, f);
  if (weighting != NormalWeighting::kAngle) return 1.0;
  const Triangle& t = mesh.faces[f];
  const Vec3& p = mesh.positions[t[c]];
  const Vec3 e1 = mesh.positions[t[(c + 1) % 3]] - p;
  const Vec3 e2 = mesh.positions[t[(c + 2) % 3]] - p;
  return std::atan2(norm(cross(e1, e2)), dot(e1, e2));
}

}  // namespace

void compute_vertex_normals(const TriMesh& mesh, NormalWeighting weighting, int threads,
                            double* out) {
  const std::size_t vertices = mesh.positions.size(), faces = mesh.faces.size();
  const int team = threads > 0 ? threads : omp_get_max_threads();
  // Each thread owns a range of vertices: it zeroes their sums (so their pages are first touched
  // by the thread that writes them), walks all faces in order and adds each weighted face normal
  // to the corners it owns, then normalises its range. Every vertex's sum is thus taken in face
  // order, as on one thread; a face with corners in two ranges has its normal computed twice.
  // (Serially, with the sums scattered by one thread: torus1m 30 ms; on 2 threads 18-20 ms,
  // docs/performance-log.md §3.)
#pragma omp parallel num_threads(team) if (team > 1 && faces >= 4096)
  {
    const auto me = static_cast<std::size_t>(omp_get_thread_num());
    const auto size = static_cast<std::size_t>(omp_get_num_threads());
    const auto lo = static_cast<std::uint32_t>(vertices * me / size);
    const auto span = static_cast<std::uint32_t>(vertices * (me + 1) / size) - lo;
    std::fill(out + 3 * std::size_t{lo}, out + 3 * (std::size_t{lo} + span), 0.0);
    for (std::size_t f = 0; f < faces; ++f) {
      const Triangle& t = mesh.faces[f];
      // Unsigned wrap-around: an index below lo is out of the range too.
      const bool mine[3] = {t[0] - lo < span, t[1] - lo < span, t[2] - lo < span};
      if (!(mine[0] || mine[1] || mine[2])) continue;
      const Vec3 n = face_normal(mesh, f);
      if (n == Vec3{}) continue;
      for (int c = 0; c < 3; ++c) {
        if (!mine[c]) continue;
        const Vec3 term = corner_weight(mesh, f, c, weighting) * n;
        double* sum = out + 3 * std::size_t{t[c]};
        for (int k = 0; k < 3; ++k) sum[k] = sum[k] + term[k];
      }
    }
    for (std::size_t v = lo; v < std::size_t{lo} + span; ++v) {
      const Vec3 sum{out[3 * v], out[3 * v + 1], out[3 * v + 2]};
      const double len = norm(sum);
      const Vec3 unit = len > 0.0 ? (1.0 / len) * sum : Vec3{};
      for (int k = 0; k < 3; ++k) out[3 * v + k] = unit[k];
    }
  }
}

std::vector<Vec3> compute_vertex_normals(const TriMesh& mesh, NormalWeighting weighting,
                                         int threads) {
  std::vector<double> flat(3 * mesh.positions.size());
  compute_vertex_normals(mesh, weighting, threads, flat.data());
  std::vector<Vec3> normals(mesh.positions.size());
  for (std::size_t v = 0; v < normals.size(); ++v)
    normals[v] = {flat[3 * v], flat[3 * v + 1], flat[3 * v + 2]};
  return normals;
}

}  // namespace meshdev
