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
// Throws ParseError naming the line. Contents of 1 MB or more (io_detail::chunks_for) are read in
// chunks of lines on `threads` OpenMP threads (0: the default): a pass counts each chunk's
// records, a second parses them; the same result and errors (any error or disagreement sends the
// file to the line-by-line parse, which names the first error's line). O(size) time and memory.
TriMesh read_off(const std::string& path, std::string_view content, int threads = 0);

namespace detail {

// read_off's chunked parse with `chunks` chunks of the records' lines (fewer where there are
// fewer lines) on `threads` threads, whatever the size: for tests, whose oracle is the
// line-by-line parse. *used_chunks (if given): whether the chunks' result is returned.
TriMesh read_off_in_chunks(const std::string& path, std::string_view content, int chunks,
                           int threads, bool* used_chunks = nullptr);

}  // namespace detail

}  // namespace meshdev
