#pragma once
// Meshes with attribute channels for the simplifier tests, and the output checks they share.
#include <string>

#include "metric/mesh.h"

namespace meshdev::test {

// icosphere(levels) with a per-vertex "normal" (the position) and a per-vertex scalar "quality".
TriMesh icosphere_with_normals(int levels);

// grid(n) with a per-vertex "color" and per-vertex "texcoord" (u, v) = (x, y).
TriMesh grid_with_color_uv(int n);

// grid(n) with a per-corner "texcoord" that has a seam along x = 0.5: corners of faces left of
// it get u = x, right of it u = x + 1.
TriMesh grid_with_uv_seam(int n);

// The named fixture: "icosphere4", "grid20", "grid20_seam", "tetrahedron".
TriMesh fixture(const std::string& name);

// Faces of zero area. O(F).
std::size_t zero_area_faces(const TriMesh& mesh);

// The largest number of faces sharing one undirected edge (0 for no faces). O(F log F).
std::size_t max_faces_per_edge(const TriMesh& mesh);

}  // namespace meshdev::test
