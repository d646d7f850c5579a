#pragma once
// Tiny meshes built in code, named for what they are, so most tests need no data file.
#include <cstdint>

#include "metric/mesh.h"

namespace meshdev::test {

// Two triangles forming the square [0,size]^2 at height z, split along its diagonal.
TriMesh square(double size = 1.0, double z = 0.0);

// An n x n grid of quads (2 n^2 triangles) over [0,size]^2 at height z.
TriMesh grid(int n, double size = 1.0, double z = 0.0);

// The regular tetrahedron with vertices (1,1,1), (1,-1,-1), (-1,1,-1), (-1,-1,1), outward faces.
TriMesh tetrahedron();

// The regular icosahedron inscribed in the unit sphere (12 vertices on the sphere).
TriMesh icosahedron();

// The icosahedron subdivided `levels` times with vertices projected onto the unit sphere.
TriMesh icosphere(int levels);

// Random triangle soup in [0,1]^3 with a fixed seed (some triangles made degenerate on purpose).
TriMesh random_soup(int triangles, std::uint64_t seed, double degenerate_fraction = 0.1);

// The same mesh moved by t.
TriMesh translated(const TriMesh& mesh, const Vec3& t);

// The same surface with its vertices and faces stored in a random order (seeded), as a file
// stored in no spatial order gives them; each face keeps its corners' order. Positions only.
TriMesh shuffled(const TriMesh& mesh, std::uint64_t seed);

}  // namespace meshdev::test
