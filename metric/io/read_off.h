#pragma once
// OFF reader (ascii): OFF, COFF, NOFF, CNOFF, STOFF and their combinations. See docs/io.md.
#include <string>
#include <string_view>

#include "metric/mesh.h"

namespace meshdev {

// Parses OFF `content` read from `path`. Vertex lines are x y z [nx ny nz] [r g b [a]] [s t]
// as the keyword says; colours are integers 0..255 (divided by 255) when every colour value in
// the file is written as an integer, floats in [0, 1] otherwise. Per-face colours after the
// indices are ignored. Polygons are fanned from their first corner. `OFF BINARY` is refused.
// Throws ParseError naming the line. O(size) time and memory.
TriMesh read_off(const std::string& path, std::string_view content);

}  // namespace meshdev
