#pragma once
// OBJ writer through write_file_atomically: v (with r g b if the mesh has per-vertex "color"),
// vt from "texcoord" (per vertex or per corner), vn from "normal" (per vertex or per corner).
#include <string>

#include "metric/mesh.h"

namespace meshdev {

struct ObjWriteOptions {
  std::string mtllib;    // written as "mtllib <name>" if not empty
  std::string material;  // written as "usemtl <name>" before the faces if not empty
};

// Writes `mesh` to `path` with shortest round-trip number formatting (read_obj reads back the
// same doubles). Per-face and scalar channels are not representable in OBJ and are left out.
// Throws WriteError on any failed write. O(V + F).
void write_obj(const std::string& path, const TriMesh& mesh, const ObjWriteOptions& options = {});

}  // namespace meshdev
