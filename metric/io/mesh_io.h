#pragma once
// Reading meshes into TriMesh and writing results, with every count, index and value checked.
// We parse the files ourselves instead of calling OpenMesh's readers: OpenMesh 9.0 hangs, throws
// bad_alloc and returns "success" with a wrong mesh on malformed files, parses into float, and
// has no per-corner UVs in PLY (docs/io.md).
#include <string>

#include "metric/mesh.h"

namespace meshdev {

// Reads OBJ, PLY (ascii, binary LE/BE), OFF (OFF/COFF/NOFF/CNOFF/STOFF) or STL (ascii/binary),
// chosen by content and extension. Polygons are triangulated as a fan from their first corner
// (v0, vi, vi+1), so per-corner attributes follow their corners. Positions in double.
// Attributes: "normal", "color" (sRGB in [0,1]), "texcoord" (per vertex or per corner), and every
// other scalar vertex property under its own name.
// Throws ParseError("<file>: <line/byte/element>: <what>") on any malformed input, IoError when
// the file cannot be opened. Never repairs silently. `threads`: OpenMP threads for the readers
// that parse in parallel (large OBJ and OFF files; 0: the default); the mesh does not depend on it.
// O(file size) time and memory.
TriMesh read_mesh(const std::string& path, int threads = 0);

}  // namespace meshdev
