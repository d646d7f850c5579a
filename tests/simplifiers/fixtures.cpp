#include "tests/simplifiers/fixtures.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <utility>

#include "tests/support/shapes.h"

namespace meshdev::test {

TriMesh icosphere_with_normals(int levels) {
  TriMesh m = icosphere(levels);
  AttributeChannel& n = m.add_channel("normal", AttributeKind::kNormal, Storage::kPerVertex, 3);
  AttributeChannel& q = m.add_channel("quality", AttributeKind::kScalar, Storage::kPerVertex, 1);
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    const Vec3& p = m.positions[v];
    n.element(v)[0] = p.x, n.element(v)[1] = p.y, n.element(v)[2] = p.z;
    q.element(v)[0] = p.z * p.z;
  }
  return m;
}

TriMesh grid_with_color_uv(int n) {
  TriMesh m = grid(n);
  AttributeChannel& c = m.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3);
  AttributeChannel& t = m.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerVertex, 2);
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    const Vec3& p = m.positions[v];
    c.element(v)[0] = p.x, c.element(v)[1] = p.y, c.element(v)[2] = 0.5;
    t.element(v)[0] = p.x, t.element(v)[1] = p.y;
  }
  return m;
}

TriMesh grid_with_uv_seam(int n) {
  TriMesh m = grid(n);
  AttributeChannel& t = m.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerCorner, 2);
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    double cx = 0;
    for (int k = 0; k < 3; ++k) cx += m.positions[m.faces[f][k]].x / 3.0;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = m.positions[m.faces[f][k]];
      t.element(3 * f + k)[0] = cx < 0.5 ? p.x : p.x + 1.0;
      t.element(3 * f + k)[1] = p.y;
    }
  }
  return m;
}

TriMesh fixture(const std::string& name) {
  if (name == "icosphere4") return icosphere_with_normals(4);
  if (name == "grid20") return grid_with_color_uv(20);
  if (name == "grid20_seam") return grid_with_uv_seam(20);
  if (name == "tetrahedron") return tetrahedron();
  throw std::invalid_argument("unknown fixture " + name);
}

std::size_t zero_area_faces(const TriMesh& mesh) {
  std::size_t n = 0;
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) n += face_area(mesh, f) == 0.0 ? 1 : 0;
  return n;
}

std::size_t max_faces_per_edge(const TriMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> count;
  std::size_t most = 0;
  for (const Triangle& t : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      std::uint32_t a = t[k], b = t[(k + 1) % 3];
      most = std::max(most, ++count[{std::min(a, b), std::max(a, b)}]);
    }
  return most;
}

}  // namespace meshdev::test
