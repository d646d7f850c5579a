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
// stderr. Contents of 1 MB or more (io_detail::chunks_for) are read in chunks of lines on `threads`
// OpenMP threads (0: the default), with the same result and the same errors (any error found
// there is reported by reading the file again line by line). O(size of content) time and memory.
TriMesh read_obj(const std::string& path, std::string_view content, int threads = 0);

namespace detail {

// read_obj's chunked parse with `chunks` chunks of lines (fewer where the text has fewer lines)
// on `threads` threads, whatever the size of the content: for tests, whose oracle is the
// line-by-line parse. Same result and errors as read_obj. *used_chunks (if given): whether the
// result is the chunks' (false: an error sent it to the line-by-line parse).
TriMesh read_obj_in_chunks(const std::string& path, std::string_view content, int chunks,
                           int threads, bool* used_chunks = nullptr);

}  // namespace detail

}  // namespace meshdev
