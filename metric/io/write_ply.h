#pragma once
// PLY writer (binary little-endian or ascii) through write_file_atomically; read_ply reads back
// everything it writes, and the per-corner UV layout is vcglib's, so MeshLab reads it too.
#include <string>
#include <vector>

#include "metric/mesh.h"

namespace meshdev {

struct PlyWriteOptions {
  bool binary = true;              // binary_little_endian; false: ascii (17 significant digits)
  bool double_positions = true;    // x y z as double; false: float
  bool double_attributes = false;  // normals, UVs and scalar channels as double; false: float
};

struct PlyWriteResult {
  std::vector<std::string> skipped_channels;  // channels PLY cannot hold (per-corner non-UV)
};

// Writes `mesh` to `path`: positions, triangles ("vertex_indices", uchar count, int indices),
// per-vertex "normal" -> nx ny nz, "color" -> red green blue (uchar, clamped to [0,1] x 255),
// "texcoord" -> u v, other per-vertex channels -> one property per component (name, or name_k
// for dim > 1); per-corner "texcoord" -> face list "texcoord" (6 values per face); per-face
// "color" -> face red green blue, other per-face channels -> face properties; texture_file ->
// "comment TextureFile" (relative to the output folder when possible).
// Throws WriteError on any failed write (see write_file_atomically). O(V + F).
PlyWriteResult write_ply(const std::string& path, const TriMesh& mesh,
                         const PlyWriteOptions& options = {});

}  // namespace meshdev
