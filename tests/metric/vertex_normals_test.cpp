#include "metric/vertex_normals.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "tests/support/shapes.h"

namespace meshdev {
namespace {

// The serial twin: each face's weighted unit normal added to its corners in face order, then
// each sum normalised (the parallel version must give these bits on any team).
std::vector<Vec3> serial_normals(const TriMesh& mesh, NormalWeighting weighting) {
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

// A sphere of 20,480 faces (enough for the parallel path) with its vertices renumbered and its
// faces reordered at random, so faces straddle the threads' vertex ranges; a few faces made
// degenerate (a repeated corner) and one vertex no face uses.
TriMesh shuffled_sphere(std::uint64_t seed) {
  TriMesh m = test::icosphere(5);
  std::mt19937_64 rng(seed);
  std::vector<std::uint32_t> renumber(m.positions.size());
  std::iota(renumber.begin(), renumber.end(), 0u);
  std::shuffle(renumber.begin(), renumber.end(), rng);
  std::vector<Vec3> positions(m.positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) positions[renumber[v]] = m.positions[v];
  m.positions = positions;
  for (Triangle& t : m.faces)
    for (std::uint32_t& v : t) v = renumber[v];
  std::shuffle(m.faces.begin(), m.faces.end(), rng);
  for (std::size_t f = 0; f < m.faces.size(); f += 997) m.faces[f][2] = m.faces[f][1];
  m.positions.push_back({5, 5, 5});
  return m;
}

void expect_same_bits(const std::vector<Vec3>& got, const std::vector<Vec3>& want) {
  ASSERT_EQ(got.size(), want.size());
  std::size_t differ = 0;
  for (std::size_t v = 0; v < got.size(); ++v)
    for (int k = 0; k < 3; ++k) differ += got[v][k] != want[v][k];
  EXPECT_EQ(differ, 0u);
}

// The team's normals are the serial twin's bit for bit, for every weighting and team size, in
// both forms (vectors and the flat array).
TEST(VertexNormals, EqualTheSerialTwinOnAnyTeam) {
  const TriMesh m = shuffled_sphere(11);
  ASSERT_GE(m.faces.size(), 4096u);
  for (NormalWeighting w :
       {NormalWeighting::kUniform, NormalWeighting::kArea, NormalWeighting::kAngle}) {
    SCOPED_TRACE(static_cast<int>(w));
    const std::vector<Vec3> want = serial_normals(m, w);
    for (int threads : {1, 2, 3, 7}) {
      SCOPED_TRACE(threads);
      expect_same_bits(compute_vertex_normals(m, w, threads), want);
      std::vector<double> flat(3 * m.positions.size(), -1.0);  // overwritten, not added to
      compute_vertex_normals(m, w, threads, flat.data());
      std::vector<Vec3> as_vectors(m.positions.size());
      for (std::size_t v = 0; v < as_vectors.size(); ++v)
        as_vectors[v] = {flat[3 * v], flat[3 * v + 1], flat[3 * v + 2]};
      expect_same_bits(as_vectors, want);
    }
  }
}

// On a sphere each vertex normal points outwards along its position (within the tessellation's
// error), and a vertex no (non-degenerate) face uses gets the zero vector.
TEST(VertexNormals, AreRadialOnASphereAndZeroWhereUnused) {
  const TriMesh m = shuffled_sphere(12);
  const std::vector<Vec3> n = compute_vertex_normals(m, NormalWeighting::kUniform, 2);
  double worst = 0.0;
  for (std::size_t v = 0; v + 1 < m.positions.size(); ++v) {
    const Vec3 radial = (1.0 / norm(m.positions[v])) * m.positions[v];
    worst = std::max(worst, norm(n[v] - radial));
  }
  EXPECT_LT(worst, 0.02);
  EXPECT_EQ(n.back(), Vec3{});
}

}  // namespace
}  // namespace meshdev
