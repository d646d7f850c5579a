// libFuzzer target: bytes -> a temporary file named .obj, .ply, .off and .stl -> read_mesh.
// Only ParseError / IoError may escape the reader, and a mesh it returns must be valid
// (finite positions, indices in range, consistent channels) with at least one vertex.
// Anything else (another exception, a sanitizer report, a hang, a huge allocation) is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include "metric/errors.h"
#include "metric/io/mesh_io.h"
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

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  char tmpl[] = "/tmp/meshdev_fuzz_read_XXXXXX";
  if (!::mkdtemp(tmpl)) std::abort();
  folder() = tmpl;
  std::cerr.setstate(std::ios::failbit);  // the readers' warnings; sanitizers write to fd 2
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  for (const char* ext : {".obj", ".ply", ".off", ".stl"}) {
    const std::string path = folder() + "/input" + ext;
    write_file(path, data, size);
    try {
      meshdev::TriMesh mesh = meshdev::read_mesh(path);
      if (mesh.num_vertices() == 0) std::abort();
      meshdev::validate(mesh, path);     // throws InvalidInput (a finding) if not
    } catch (const meshdev::IoError&) {  // ParseError derives from IoError
    }
  }
  return 0;
}
