#include "metric/io/write_ply.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <ostream>

#include "metric/io/atomic_file.h"

namespace meshdev {
namespace {

enum class Kind { kUchar, kInt, kFloat, kDouble };

const char* type_name(Kind k) {
  switch (k) {
    case Kind::kUchar:
      return "uchar";
    case Kind::kInt:
      return "int";
    case Kind::kFloat:
      return "float";
    case Kind::kDouble:
      return "double";
  }
  return "?";
}

// One output property: a component of a channel (or of the positions).
struct Column {
  std::string name;
  Kind kind;
  const AttributeChannel* channel;  // nullptr: positions
  int component;
  double scale;  // colours: x 255
};

// Writes values in binary little-endian or ascii.
class Emitter {
 public:
  Emitter(std::ostream& out, bool binary) : out_(out), binary_(binary) {}
  void value(Kind kind, double v) {
    if (binary_) {
      switch (kind) {
        case Kind::kUchar:
          put(static_cast<unsigned char>(v));
          break;
        case Kind::kInt:
          put(static_cast<std::int32_t>(v));
          break;
        case Kind::kFloat:
          put(static_cast<float>(v));
          break;
        case Kind::kDouble:
          put(v);
          break;
      }
      return;
    }
    if (!first_) out_.put(' ');
    first_ = false;
    char buf[32];
    std::to_chars_result r =
        kind == Kind::kFloat ? std::to_chars(buf, buf + sizeof buf, static_cast<float>(v))
        : kind == Kind::kDouble
            ? std::to_chars(buf, buf + sizeof buf, v)
            : std::to_chars(buf, buf + sizeof buf, static_cast<std::int64_t>(v));
    out_.write(buf, r.ptr - buf);
  }
  void end_record() {
    if (!binary_) out_.put('\n');
    first_ = true;
  }

 private:
  template <class T>
  void put(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));  // little-endian host
    out_.write(b, sizeof(T));
  }
  std::ostream& out_;
  bool binary_;
  bool first_ = true;
};

double color_byte(double c) {
  return std::round(std::clamp(c, 0.0, 1.0) * 255.0);
}

}  // namespace

PlyWriteResult write_ply(const std::string& path, const TriMesh& mesh,
                         const PlyWriteOptions& options) {
  PlyWriteResult result;
  const Kind pos_kind = options.double_positions ? Kind::kDouble : Kind::kFloat;
  const Kind attr_kind = options.double_attributes ? Kind::kDouble : Kind::kFloat;

  // Plan the columns of both elements.
  std::vector<Column> vcols, fcols;
  for (int k = 0; k < 3; ++k) vcols.push_back({std::string(1, "xyz"[k]), pos_kind, nullptr, k, 1});
  const AttributeChannel* corner_uv = nullptr;
  for (const AttributeChannel& c : mesh.channels) {
    if (c.storage == Storage::kPerCorner) {
      if (c.kind == AttributeKind::kTexCoord && c.dim == 2 && !corner_uv)
        corner_uv = &c;
      else
        result.skipped_channels.push_back(c.name);
      continue;
    }
    std::vector<Column>& cols = c.storage == Storage::kPerVertex ? vcols : fcols;
    if (c.kind == AttributeKind::kColor && c.dim == 3) {
      for (int k = 0; k < 3; ++k)
        cols.push_back({k == 0 ? "red" : k == 1 ? "green" : "blue", Kind::kUchar, &c, k, 255});
    } else if (c.kind == AttributeKind::kNormal && c.dim == 3) {
      for (int k = 0; k < 3; ++k)
        cols.push_back({std::string("n") + "xyz"[k], attr_kind, &c, k, 1});
    } else if (c.kind == AttributeKind::kTexCoord && c.dim == 2) {
      for (int k = 0; k < 2; ++k) cols.push_back({k == 0 ? "u" : "v", attr_kind, &c, k, 1});
    } else {
      for (int k = 0; k < c.dim; ++k)
        cols.push_back(
            {c.dim == 1 ? c.name : c.name + "_" + std::to_string(k), attr_kind, &c, k, 1});
    }
  }

  std::string texture = mesh.texture_file;
  if (!texture.empty()) {
    std::filesystem::path folder = std::filesystem::absolute(path).parent_path();
    std::error_code ec;
    std::filesystem::path rel = std::filesystem::absolute(texture).lexically_relative(folder);
    if (!rel.empty()) texture = rel.string();
  }

  write_file_atomically(path, [&](std::ostream& out) {
    out << "ply\nformat " << (options.binary ? "binary_little_endian" : "ascii") << " 1.0\n"
        << "comment meshdev\n";
    if (!texture.empty()) out << "comment TextureFile " << texture << '\n';
    out << "element vertex " << mesh.positions.size() << '\n';
    for (const Column& c : vcols) out << "property " << type_name(c.kind) << ' ' << c.name << '\n';
    out << "element face " << mesh.faces.size() << '\n'
        << "property list uchar int vertex_indices\n";
    if (corner_uv) out << "property list uchar " << type_name(attr_kind) << " texcoord\n";
    for (const Column& c : fcols) out << "property " << type_name(c.kind) << ' ' << c.name << '\n';
    out << "end_header\n";

    Emitter e(out, options.binary);
    auto emit = [&e](const Column& c, std::size_t i) {
      double v = c.channel ? c.channel->element(i)[c.component] : 0.0;
      e.value(c.kind, c.scale == 255 ? color_byte(v) : v);
    };
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      for (const Column& c : vcols)
        c.channel ? emit(c, v) : e.value(c.kind, mesh.positions[v][c.component]);
      e.end_record();
    }
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      e.value(Kind::kUchar, 3);
      for (std::uint32_t v : mesh.faces[f]) e.value(Kind::kInt, v);
      if (corner_uv) {
        e.value(Kind::kUchar, 6);
        for (int k = 0; k < 6; ++k) e.value(attr_kind, corner_uv->values[6 * f + k]);
      }
      for (const Column& c : fcols) emit(c, f);
      e.end_record();
    }
  });
  return result;
}

}  // namespace meshdev
