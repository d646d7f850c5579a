// meshdev info FILE: read a mesh with the validating readers and describe it.
#include <CLI/CLI.hpp>
#include <iostream>

#include "apps/commands.h"
#include "apps/exit_codes.h"
#include "metric/io/mesh_io.h"
#include "metric/mesh.h"

namespace meshdev::app {
namespace {

const char* storage_name(Storage s) {
  switch (s) {
    case Storage::kPerVertex:
      return "per vertex";
    case Storage::kPerCorner:
      return "per corner";
    case Storage::kPerFace:
      return "per face";
  }
  return "?";
}

int run_info(const std::string& path) {
  TriMesh mesh = read_mesh(path);
  std::vector<bool> used = referenced_vertices(mesh);
  std::size_t unreferenced = 0;
  for (bool u : used) unreferenced += u ? 0 : 1;
  std::size_t degenerate = 0;
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) degenerate += face_area(mesh, f) == 0.0;
  BoundingBox box = bounding_box(mesh);
  std::cout << "file          " << path << '\n'
            << "vertices      " << mesh.num_vertices() << " (" << unreferenced << " unreferenced)\n"
            << "triangles     " << mesh.num_faces() << " (from " << mesh.source_polygons
            << " polygons; " << degenerate << " of zero area)\n"
            << "area          " << surface_area(mesh) << '\n'
            << "bbox diagonal " << box.diagonal() << '\n';
  for (const AttributeChannel& c : mesh.channels)
    std::cout << "attribute     " << c.name << " (dim " << c.dim << ", " << storage_name(c.storage)
              << ")\n";
  if (!mesh.texture_file.empty()) std::cout << "texture       " << mesh.texture_file << '\n';
  return kOk;
}

}  // namespace

void add_info_command(CLI::App& root, int& exit_code) {
  auto* cmd = root.add_subcommand("info", "Read a mesh (OBJ, PLY, OFF, STL) and describe it");
  auto path = std::make_shared<std::string>();
  cmd->add_option("file", *path, "mesh file")->required();
  cmd->callback([path, &exit_code] { exit_code = run_info(*path); });
}

}  // namespace meshdev::app
