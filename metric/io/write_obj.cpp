#include "metric/io/write_obj.h"

#include <charconv>
#include <ostream>

#include "metric/io/atomic_file.h"

namespace meshdev {
namespace {

void put(std::ostream& out, double v) {
  char buf[32];
  std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v);
  out.put(' ');
  out.write(buf, r.ptr - buf);
}

const AttributeChannel* find(const TriMesh& mesh, const char* name, AttributeKind kind, int dim) {
  const AttributeChannel* c = mesh.channel(name);
  if (c && c->kind == kind && c->dim == dim && c->storage != Storage::kPerFace) return c;
  return nullptr;
}

}  // namespace

void write_obj(const std::string& path, const TriMesh& mesh, const ObjWriteOptions& options) {
  const AttributeChannel* color = mesh.channel("color");
  if (color && (color->storage != Storage::kPerVertex || color->dim != 3)) color = nullptr;
  const AttributeChannel* uv = find(mesh, "texcoord", AttributeKind::kTexCoord, 2);
  const AttributeChannel* normal = find(mesh, "normal", AttributeKind::kNormal, 3);

  write_file_atomically(path, [&](std::ostream& out) {
    out << "# meshdev\n";
    if (!options.mtllib.empty()) out << "mtllib " << options.mtllib << '\n';
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      out << 'v';
      for (int k = 0; k < 3; ++k) put(out, mesh.positions[v][k]);
      if (color)
        for (int k = 0; k < 3; ++k) put(out, color->element(v)[k]);
      out << '\n';
    }
    // vt/vn records: one per vertex (per-vertex channel) or one per corner (per-corner channel).
    auto records = [&out](const AttributeChannel* c, const char* key) {
      if (!c) return;
      for (std::size_t i = 0; i < c->element_count(); ++i) {
        out << key;
        for (int k = 0; k < c->dim; ++k) put(out, c->element(i)[k]);
        out << '\n';
      }
    };
    records(uv, "vt");
    records(normal, "vn");
    if (!options.material.empty()) out << "usemtl " << options.material << '\n';
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      out << 'f';
      for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t v = mesh.faces[f][c];
        out << ' ' << v + 1;
        auto ref = [&](const AttributeChannel* ch) {
          return (ch->storage == Storage::kPerVertex ? v : 3 * f + c) + 1;
        };
        if (uv) out << '/' << ref(uv);
        if (normal) out << (uv ? "/" : "//") << ref(normal);
      }
      out << '\n';
    }
  });
}

}  // namespace meshdev
