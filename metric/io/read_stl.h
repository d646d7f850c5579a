#pragma once
// STL reader, ascii and binary. See docs/io.md.
#include <string>
#include <string_view>

#include "metric/mesh.h"

namespace meshdev {

// Parses STL `content` read from `path`. Binary when the size is exactly 84 + 50 n (n = the
// header's triangle count), even if the header starts with "solid"; ascii otherwise when it
// starts with "solid". Corners with bit-identical positions are merged into one vertex, in order
// of first appearance. No attribute channels (STL facet normals are dropped; never invented).
// Throws ParseError ("byte N" / "line N") on malformed input or a file without triangles.
// O(size) expected time and memory.
TriMesh read_stl(const std::string& path, std::string_view content);

}  // namespace meshdev
