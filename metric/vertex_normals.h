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

// Unit normal per vertex; (0,0,0) for a vertex with no non-degenerate incident face. Each
// vertex's weighted face normals are summed in face order, so the result does not depend on
// `threads` (OpenMP threads, 0 = OpenMP's default). Precondition: validate(mesh) passes (face
// indices in range). O(V + F) work; each thread reads every face's indices once.
std::vector<Vec3> compute_vertex_normals(const TriMesh& mesh, NormalWeighting weighting,
                                         int threads = 0);

// The same normals written to out[3 v], out[3 v + 1], out[3 v + 2] for each vertex v (out holds
// 3 V doubles, overwritten), each thread writing the vertices it sums: for callers that keep them
// as a flat channel (metric/attributes.cpp) without a copy.
void compute_vertex_normals(const TriMesh& mesh, NormalWeighting weighting, int threads,
                            double* out);

// Unit normal of face f, or (0,0,0) if the face is degenerate. O(1).
Vec3 face_normal(const TriMesh& mesh, std::size_t f);

}  // namespace meshdev
