#pragma once
// Writing an output so that it is either complete or absent: earlier results are never left
// half-overwritten, and every write/flush/fsync/close/rename is checked.
#include <functional>
#include <ostream>
#include <string>

namespace meshdev {

// Calls body(stream) to produce the file's bytes, writing them to "<path>.tmp.<pid>" in the same
// folder, then fsyncs, closes and renames it over `path` (a symlink is followed: its target is
// replaced). If `path` is an existing non-regular file (/dev/null, /dev/full, a FIFO) the bytes
// are written to it directly. Throws WriteError("<path>: <what> (<strerror>)") on any failure,
// after removing the temporary file; an exception from `body` is rethrown after the same cleanup.
// O(bytes written); buffers 64 KiB.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& body);

// Checks, before the work whose result goes to `path`, that it can be written there: its folder
// exists and is a folder the process may write in, and `path` itself is not a folder. Throws
// WriteError("<path>: <what> (<strerror>)") otherwise, so that a long computation is not lost
// to a mistyped output folder. Nothing is created. O(1) system calls.
void check_output_path(const std::string& path);

// Creates `folder` and its missing parents (an output folder named by the user); throws
// WriteError("<folder>: cannot create the folder (<reason>)") if that fails or a file of that
// name is in the way. O(depth) system calls.
void make_output_folder(const std::string& folder);

}  // namespace meshdev
