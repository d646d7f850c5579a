// Inputs for the peer comparison (bench/peers/make_inputs.sh):
//   peer_mesh_tool torus NU NV OUT.ply   bumpy torus with exactly 2 x NU x NV triangles
//   peer_mesh_tool convert IN OUT.ply    any mesh meshdev reads -> PLY (MeshLab cannot read our
//                                        OBJ files: simplifiers.md §5)
//   peer_mesh_tool shuffle IN OUT.ply SEED  the same mesh with its faces in a random order (the
//                                        order of many tools' output): no face near the one
//                                        stored before it
// PLY positions are written as float so that meshdev, Embree, CGAL and MeshLab all read the very
// same coordinates.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <random>
#include <stdexcept>
#include <string>

#include "metric/io/mesh_io.h"
#include "metric/io/write_ply.h"
#include "metric/mesh.h"

namespace {

// Torus with major radius 1 and minor radius 0.35, its tube radius modulated by two sine
// bumps, so a simplification has real, varying geometric error. Grid of NU x NV quads, each
// split in two triangles, closed in both directions.
meshdev::TriMesh bumpy_torus(int nu, int nv) {
  constexpr double kPi = 3.14159265358979323846;
  meshdev::TriMesh m;
  m.positions.reserve(static_cast<std::size_t>(nu) * nv);
  for (int i = 0; i < nu; ++i) {
    const double u = 2 * kPi * i / nu;
    for (int j = 0; j < nv; ++j) {
      const double v = 2 * kPi * j / nv;
      const double r =
          0.35 * (1 + 0.12 * std::sin(9 * u) * std::sin(4 * v) + 0.04 * std::sin(31 * u + 3 * v));
      const double R = 1 + r * std::cos(v);
      m.positions.push_back({R * std::cos(u), R * std::sin(u), r * std::sin(v)});
    }
  }
  auto id = [&](int i, int j) {
    return static_cast<std::uint32_t>(((i + nu) % nu) * nv + (j + nv) % nv);
  };
  m.faces.reserve(2 * static_cast<std::size_t>(nu) * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

int usage() {
  std::fprintf(stderr,
               "usage: peer_mesh_tool torus NU NV OUT.ply   (2*NU*NV faces)\n"
               "       peer_mesh_tool convert IN OUT.ply\n"
               "       peer_mesh_tool shuffle IN OUT.ply SEED\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    meshdev::PlyWriteOptions ply;
    ply.double_positions = false;
    if (argc == 5 && std::string(argv[1]) == "torus") {
      const int nu = std::atoi(argv[2]), nv = std::atoi(argv[3]);
      if (nu < 3 || nv < 3) return usage();
      const meshdev::TriMesh m = bumpy_torus(nu, nv);
      meshdev::write_ply(argv[4], m, ply);
      std::printf("%s: %zu vertices, %zu faces\n", argv[4], m.num_vertices(), m.num_faces());
      return 0;
    }
    if (argc == 4 && std::string(argv[1]) == "convert") {
      const meshdev::TriMesh m = meshdev::read_mesh(argv[2]);
      meshdev::write_ply(argv[3], m, ply);
      std::printf("%s: %zu vertices, %zu faces\n", argv[3], m.num_vertices(), m.num_faces());
      return 0;
    }
    if (argc == 5 && std::string(argv[1]) == "shuffle") {
      meshdev::TriMesh m = meshdev::read_mesh(argv[2]);
      for (const meshdev::AttributeChannel& c : m.channels)
        if (c.storage != meshdev::Storage::kPerVertex)
          throw std::runtime_error(std::string(argv[2]) + ": channel '" + c.name +
                                   "' is stored per face or corner; shuffle keeps only "
                                   "per-vertex channels in step with the faces");
      std::mt19937_64 rng(std::strtoull(argv[4], nullptr, 10));
      std::shuffle(m.faces.begin(), m.faces.end(), rng);
      meshdev::write_ply(argv[3], m, ply);
      std::printf("%s: %zu vertices, %zu faces (shuffled)\n", argv[3], m.num_vertices(),
                  m.num_faces());
      return 0;
    }
    return usage();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "peer_mesh_tool: %s\n", e.what());
    return 1;
  }
}
