#pragma once
// Wavefront OBJ reader: v (optionally with r g b [a]), vt, vn, f with v, v/vt, v//vn, v/vt/vn and
// negative (relative) indices, polygons, mtllib/usemtl/map_Kd. See docs/io.md.
#include <string>
#include <string_view>

#include "metric/mesh.h"

namespace meshdev {

// Parses OBJ `content` read from `path` (used for messages and to find the .mtl file).
// Polygons are fanned from their first corner. UVs/normals become "texcoord"/"normal" channels,
// per vertex when every vertex is used and always gets the same vt/vn, per corner otherwise.
// Throws ParseError naming the line on any malformed record; a missing .mtl is a warning on
// stderr. O(size of content) time and memory.
TriMesh read_obj(const std::string& path, std::string_view content);

}  // namespace meshdev
