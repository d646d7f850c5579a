// libFuzzer target: bytes -> a temporary file named .obj, .ply, .off and .stl -> read_mesh.
// Only ParseError / IoError may escape the reader, and a mesh it returns must be valid
// (finite positions, indices in range, consistent channels) with at least one vertex.
// Anything else (another exception, a sanitizer report, a hang, a huge allocation) is a finding.
// The bytes are also parsed as OBJ and as OFF in 3 chunks of lines (the readers' parse of large
// files), which must give the line-by-line parse's mesh or its error message.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <string_view>

#include "metric/errors.h"
#include "metric/io/mesh_io.h"
#include "metric/io/read_obj.h"
#include "metric/io/read_off.h"
#include "metric/mesh.h"

namespace {

std::string& folder() {
  static std::string dir;
  return dir;
}

void write_file(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size && std::fwrite(data, 1, size, f) != size) std::abort();
  if (std::fclose(f) != 0) std::abort();
}

// A chunked parse against the line-by-line one: the same error, or the same mesh bit for bit (a
// difference aborts: a finding).
template <class LineByLine, class Chunked>
void check_chunks(LineByLine line_by_line, Chunked chunked) {
  std::string want_error, got_error;
  meshdev::TriMesh want, got;
  try {
    want = line_by_line();
  } catch (const meshdev::IoError& e) {
    want_error = e.what();
  }
  try {
    got = chunked();
  } catch (const meshdev::IoError& e) {
    got_error = e.what();
  }
  if (got_error != want_error) std::abort();
  if (!want_error.empty()) return;
  bool same = got.faces == want.faces && got.positions.size() == want.positions.size() &&
              got.channels.size() == want.channels.size() &&
              got.source_polygons == want.source_polygons && got.texture_file == want.texture_file;
  for (std::size_t v = 0; same && v < got.positions.size(); ++v)
    same = std::memcmp(&got.positions[v], &want.positions[v], sizeof(meshdev::Vec3)) == 0;
  for (std::size_t c = 0; same && c < got.channels.size(); ++c)
    same = got.channels[c].name == want.channels[c].name &&
           got.channels[c].storage == want.channels[c].storage &&
           got.channels[c].values.size() == want.channels[c].values.size() &&
           std::memcmp(got.channels[c].values.data(), want.channels[c].values.data(),
                       got.channels[c].values.size() * sizeof(double)) == 0;
  if (!same) std::abort();
}

constexpr const char* kExtensions[] = {".obj", ".ply", ".off", ".stl"};

// Removes the inputs' folder when the fuzzer exits (libFuzzer ends a timed run with exit()); a
// crash leaves it, and libFuzzer keeps the input that crashed. Each run used to leave one behind.
void remove_folder() {
  for (const char* ext : kExtensions) std::remove((folder() + "/input" + ext).c_str());
  ::rmdir(folder().c_str());
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  char tmpl[] = "/tmp/meshdev_fuzz_read_XXXXXX";
  if (!::mkdtemp(tmpl)) std::abort();
  folder() = tmpl;
  if (std::atexit(remove_folder) != 0) std::abort();
  std::cerr.setstate(std::ios::failbit);  // the readers' warnings; sanitizers write to fd 2
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  for (const char* ext : kExtensions) {
    const std::string path = folder() + "/input" + ext;
    write_file(path, data, size);
    try {
      meshdev::TriMesh mesh = meshdev::read_mesh(path);
      if (mesh.num_vertices() == 0) std::abort();
      meshdev::validate(mesh, path);     // throws InvalidInput (a finding) if not
    } catch (const meshdev::IoError&) {  // ParseError derives from IoError
    }
  }
  const std::string_view content(reinterpret_cast<const char*>(data), size);
  const std::string obj = folder() + "/input.obj", off = folder() + "/input.off";
  check_chunks([&] { return meshdev::read_obj(obj, content, 1); },
               [&] { return meshdev::detail::read_obj_in_chunks(obj, content, 3, 1); });
  check_chunks([&] { return meshdev::read_off(off, content, 1); },
               [&] { return meshdev::detail::read_off_in_chunks(off, content, 3, 1); });
  return 0;
}
