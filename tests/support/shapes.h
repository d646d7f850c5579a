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

// Triangles for the build's four-lane kernels (metric/face_boxes.h, metric/leaf_blocks.h), seeded:
// each at a scale from 1e-6 to 1e2 around a point up to 50 from the origin; face f with f % 5 == 1
// a sliver (its third corner 1e-9 of its scale off the line of the first two: kappa past
// kMaxCullKappa), == 2 a repeated corner (|ab x ac| = 0), == 3 a corner shared with the face
// before. Unreferenced vertices are left in.
TriMesh kernel_soup(std::uint32_t faces, std::uint64_t seed);

// The same mesh moved by t.
TriMesh translated(const TriMesh& mesh, const Vec3& t);

// The same surface with its vertices and faces stored in a random order (seeded), as a file
// stored in no spatial order gives them; each face keeps its corners' order. Positions only.
TriMesh shuffled(const TriMesh& mesh, std::uint64_t seed);

}  // namespace meshdev::test
