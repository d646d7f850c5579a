#pragma once
// PLY reader: ascii, binary_little_endian and binary_big_endian; every scalar type; list
// properties with any count/item type; unknown elements skipped. See docs/io.md.
#include <string>
#include <string_view>

#include "metric/mesh.h"

namespace meshdev {

// Parses PLY `content` read from `path`. Vertex x y z are required; nx ny nz -> "normal",
// red green blue -> "color" (integers / 255, floats as is), alpha -> "alpha", u v / s t /
// texture_u texture_v / texture_s texture_t -> per-vertex "texcoord", every other scalar vertex
// property -> a per-vertex scalar channel of the same name. Faces: vertex_indices (or
// vertex_index) fanned from the first corner, per-face `texcoord` list -> per-corner "texcoord",
// face red green blue -> per-face "color", other face scalars -> per-face channels ("face_"
// prefixed if a vertex channel has the name). Every count is checked against the bytes present
// before allocating. Throws ParseError ("line N" / "byte N" / "face N"). O(size) time and memory.
TriMesh read_ply(const std::string& path, std::string_view content);

}  // namespace meshdev
