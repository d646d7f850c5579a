#include "metric/io/write_atlas.h"

#include <ostream>

#include "metric/io/atomic_file.h"
#include "metric/io/write_obj.h"
#include "metric/io/write_ply.h"
#include "metric/io/write_png.h"

namespace meshdev {
namespace {

std::string base_name(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

void write_deviation_atlas(const std::string& stem, const DeviationAtlas& atlas) {
  const std::string png = stem + ".png", name = base_name(stem);
  write_png(png, atlas.image);
  write_file_atomically(stem + ".mtl", [&](std::ostream& out) {
    out << "# meshdev deviation atlas\nnewmtl deviation\nKa 1 1 1\nKd 1 1 1\nKs 0 0 0\nillum 1\n"
        << "map_Kd " << name << ".png\n";
  });
  write_obj(stem + ".obj", atlas.mesh, ObjWriteOptions{name + ".mtl", "deviation"});
  TriMesh with_texture = atlas.mesh;
  with_texture.texture_file = png;
  write_ply(stem + ".ply", with_texture);
}

}  // namespace meshdev
