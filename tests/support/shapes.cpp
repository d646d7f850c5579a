#include "tests/support/shapes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>

namespace meshdev::test {

TriMesh square(double size, double z) {
  return grid(1, size, z);
}

TriMesh grid(int n, double size, double z) {
  TriMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.positions.push_back({size * i / n, size * j / n, z});
  auto id = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  m.source_polygons = m.faces.size();
  return m;
}

TriMesh tetrahedron() {
  TriMesh m;
  m.positions = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  m.source_polygons = 4;
  return m;
}

TriMesh icosahedron() {
  TriMesh m;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double s = 1.0 / std::sqrt(1.0 + t * t);
  const double a = s, b = t * s;
  m.positions = {{-a, b, 0},  {a, b, 0},  {-a, -b, 0}, {a, -b, 0}, {0, -a, b},  {0, a, b},
                 {0, -a, -b}, {0, a, -b}, {b, 0, -a},  {b, 0, a},  {-b, 0, -a}, {-b, 0, a}};
  m.faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  m.source_polygons = 20;
  return m;
}

TriMesh icosphere(int levels) {
  TriMesh m = icosahedron();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t i, std::uint32_t j) {
      auto key = std::minmax(i, j);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      Vec3 p = 0.5 * (m.positions[i] + m.positions[j]);
      p = (1.0 / norm(p)) * p;
      m.positions.push_back(p);
      std::uint32_t id = static_cast<std::uint32_t>(m.positions.size() - 1);
      mid.emplace(key, id);
      return id;
    };
    std::vector<Triangle> faces;
    for (const Triangle& t : m.faces) {
      std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      faces.push_back({t[0], ab, ca});
      faces.push_back({t[1], bc, ab});
      faces.push_back({t[2], ca, bc});
      faces.push_back({ab, bc, ca});
    }
    m.faces = std::move(faces);
  }
  m.source_polygons = m.faces.size();
  return m;
}

TriMesh kernel_soup(std::uint32_t faces, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  TriMesh m;
  for (std::uint32_t f = 0; f < faces; ++f) {
    const double scale = std::pow(10.0, static_cast<int>(rng() % 9) - 6);  // 1e-6 .. 1e2
    const Vec3 centre{50 * unit(rng), 50 * unit(rng), 50 * unit(rng)};
    Triangle t;
    for (auto& id : t) {
      m.positions.push_back(centre + scale * Vec3{unit(rng), unit(rng), unit(rng)});
      id = static_cast<std::uint32_t>(m.positions.size() - 1);
    }
    switch (f % 5) {
      case 1:  // a sliver: the third corner nearly on the line of the first two
        m.positions[t[2]] =
            0.5 * (m.positions[t[0]] + m.positions[t[1]]) + Vec3{0, 0, 1e-9 * scale};
        break;
      case 2:  // a repeated corner
        t[2] = t[0];
        break;
      case 3:  // a corner of the face before
        if (f > 0) t[1] = m.faces[f - 1][0];
        break;
      default:
        break;
    }
    m.faces.push_back(t);
  }
  return m;
}

TriMesh random_soup(int triangles, std::uint64_t seed, double degenerate_fraction) {
  std::mt19937_64 rng(seed);
  auto uniform = [&rng] { return static_cast<double>(rng() >> 11) * 0x1p-53; };
  TriMesh m;
  for (int i = 0; i < triangles; ++i) {
    Vec3 a{uniform(), uniform(), uniform()};
    Vec3 b = a + 0.2 * Vec3{uniform() - 0.5, uniform() - 0.5, uniform() - 0.5};
    Vec3 c = a + 0.2 * Vec3{uniform() - 0.5, uniform() - 0.5, uniform() - 0.5};
    double kind = uniform();
    if (kind < degenerate_fraction / 2)
      c = a + 0.37 * (b - a);  // collinear: zero area
    else if (kind < degenerate_fraction)
      c = b;  // repeated corner
    auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {a, b, c});
    m.faces.push_back({base, base + 1, base + 2});
  }
  m.source_polygons = m.faces.size();
  return m;
}

TriMesh translated(const TriMesh& mesh, const Vec3& t) {
  TriMesh m = mesh;
  for (Vec3& p : m.positions) p = p + t;
  return m;
}

TriMesh shuffled(const TriMesh& mesh, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::uint32_t> to(mesh.positions.size());
  for (std::uint32_t v = 0; v < to.size(); ++v) to[v] = v;
  std::shuffle(to.begin(), to.end(), rng);
  TriMesh m;
  m.positions.resize(mesh.positions.size());
  for (std::uint32_t v = 0; v < to.size(); ++v) m.positions[to[v]] = mesh.positions[v];
  for (const Triangle& t : mesh.faces) m.faces.push_back({to[t[0]], to[t[1]], to[t[2]]});
  std::shuffle(m.faces.begin(), m.faces.end(), rng);
  return m;
}

}  // namespace meshdev::test
