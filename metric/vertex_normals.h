#pragma once
// Per-vertex normals computed from the geometry, for meshes whose file has none (or when the
// comparison asks for computed normals on both meshes).
#include <vector>

#include "metric/mesh.h"

namespace meshdev {

enum class NormalWeighting {
  kUniform,  // plain average of the incident face normals (the paper's §5 choice)
  kArea,     // face normals weighted by face area
  kAngle,    // weighted by the face's angle at the vertex (Thürmer & Wüthrich 1998)
};

// Unit normal per vertex; (0,0,0) for a vertex with no non-degenerate incident face.
// O(V + F).
std::vector<Vec3> compute_vertex_normals(const TriMesh& mesh, NormalWeighting weighting);

// Unit normal of face f, or (0,0,0) if the face is degenerate. O(1).
Vec3 face_normal(const TriMesh& mesh, std::size_t f);

}  // namespace meshdev
