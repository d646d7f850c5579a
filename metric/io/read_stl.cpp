#include "metric/io/read_stl.h"

#include <cmath>
#include <cstring>
#include <unordered_map>

#include "metric/errors.h"
#include "metric/io/text_scan.h"

namespace meshdev {
namespace {

using io_detail::NumberStatus;
using io_detail::quoted;

struct PositionKey {
  std::uint64_t bits[3];
  bool operator==(const PositionKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};

struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = 0x9E3779B97F4A7C15ull;
    for (std::uint64_t b : k.bits) h = (h ^ b) * 0xBF58476D1CE4E5B9ull, h ^= h >> 31;
    return static_cast<std::size_t>(h);
  }
};

// Joins corners with bit-identical positions into shared vertices, in order of first appearance.
class VertexMerger {
 public:
  explicit VertexMerger(TriMesh& mesh, std::size_t corners) : mesh_(mesh) { map_.reserve(corners); }
  std::uint32_t add(const Vec3& p) {
    PositionKey key;
    for (int k = 0; k < 3; ++k) {
      double c = p[k];
      std::memcpy(&key.bits[k], &c, 8);
    }
    auto [it, inserted] = map_.emplace(key, static_cast<std::uint32_t>(mesh_.positions.size()));
    if (inserted) mesh_.positions.push_back(p);
    return it->second;
  }

 private:
  TriMesh& mesh_;
  std::unordered_map<PositionKey, std::uint32_t, PositionHash> map_;
};

TriMesh read_binary(const std::string& path, std::string_view data, std::uint32_t count) {
  TriMesh mesh;
  mesh.source_file = path;
  mesh.faces.reserve(count);
  VertexMerger merger(mesh, std::size_t{count} * 3 / 2);
  for (std::uint32_t f = 0; f < count; ++f) {
    const std::size_t base = 84 + 50 * std::size_t{f};
    Triangle t;
    for (int c = 0; c < 3; ++c) {
      float xyz[3];  // little-endian in the file, as on every host we build for
      std::memcpy(xyz, data.data() + base + 12 + 12 * c, 12);
      for (float& x : xyz) {
        if (!std::isfinite(x))
          throw ParseError(path, "byte " + std::to_string(base + 12 + 12 * c),
                           "face " + std::to_string(f) + ": corner " + std::to_string(c) +
                               " has a non-finite coordinate");
      }
      t[c] = merger.add({xyz[0], xyz[1], xyz[2]});
    }
    mesh.faces.push_back(t);
  }
  mesh.source_polygons = count;
  return mesh;
}

// Token stream over the whole ascii text with line numbers for messages.
class AsciiStl {
 public:
  AsciiStl(const std::string& path, std::string_view text) : path_(path), text_(text) {}
  TriMesh parse();

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw ParseError(path_, "line " + std::to_string(line_), what);
  }
  bool next(std::string_view& tok) {
    while (pos_ < text_.size() && io_detail::is_space(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ >= text_.size()) return false;
    std::size_t b = pos_;
    while (pos_ < text_.size() && !io_detail::is_space(text_[pos_])) ++pos_;
    tok = text_.substr(b, pos_ - b);
    return true;
  }
  void skip_rest_of_line() {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  }
  void expect(std::string_view word) {
    std::string_view tok;
    if (!next(tok)) fail("file ends where '" + std::string(word) + "' was expected (truncated)");
    if (tok != word) fail("expected '" + std::string(word) + "', found " + quoted(tok));
  }
  double number(bool finite_required) {
    std::string_view tok;
    if (!next(tok)) fail("file ends inside a facet (truncated)");
    double v = 0;
    NumberStatus s = io_detail::parse_double(tok, v);
    if (s == NumberStatus::kNotNumber || (s != NumberStatus::kOk && finite_required))
      fail(io_detail::describe_bad_number(tok, s));
    return v;
  }

  const std::string& path_;
  std::string_view text_;
  std::size_t pos_ = 0, line_ = 1;
};

TriMesh AsciiStl::parse() {
  TriMesh mesh;
  mesh.source_file = path_;
  VertexMerger merger(mesh, text_.size() / 100);
  std::string_view tok;
  while (next(tok)) {
    if (tok != "solid") fail("expected 'solid', found " + quoted(tok));
    skip_rest_of_line();  // the solid's name
    for (;;) {
      if (!next(tok)) fail("file ends before 'endsolid' (truncated)");
      if (tok == "endsolid") {
        skip_rest_of_line();
        break;
      }
      if (tok != "facet") fail("expected 'facet' or 'endsolid', found " + quoted(tok));
      expect("normal");
      for (int k = 0; k < 3; ++k) number(false);  // facet normals are not used
      expect("outer");
      expect("loop");
      Triangle t;
      for (int c = 0; c < 3; ++c) {
        if (!next(tok)) fail("file ends inside a facet (truncated)");
        if (tok == "endloop")
          fail("facet with " + std::to_string(c) + " vertices (exactly 3 needed)");
        if (tok != "vertex") fail("expected 'vertex', found " + quoted(tok));
        Vec3 p;
        for (int k = 0; k < 3; ++k) p[k] = number(true);
        t[c] = merger.add(p);
      }
      if (!next(tok)) fail("file ends inside a facet (truncated)");
      if (tok == "vertex") fail("facet with more than 3 vertices (exactly 3 needed)");
      if (tok != "endloop") fail("expected 'endloop', found " + quoted(tok));
      expect("endfacet");
      mesh.faces.push_back(t);
    }
  }
  mesh.source_polygons = mesh.faces.size();
  return mesh;
}

bool starts_with_solid(std::string_view text) {
  text = io_detail::trim(text.substr(0, 512));
  return text.size() >= 5 && text.substr(0, 5) == "solid" &&
         (text.size() == 5 || io_detail::is_space(text[5]));
}

}  // namespace

TriMesh read_stl(const std::string& path, std::string_view content) {
  if (content.empty()) throw ParseError(path, "", "empty file");
  TriMesh mesh;
  const bool solid = starts_with_solid(io_detail::strip_bom(content));
  std::string size_problem;
  if (content.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, content.data() + 80, 4);
    const std::uint64_t expected = 84 + 50 * std::uint64_t{count};
    if (expected == content.size()) {
      mesh = read_binary(path, content, count);
      if (mesh.faces.empty()) throw ParseError(path, "byte 80", "binary STL with 0 triangles");
      return mesh;
    }
    size_problem = "binary STL header says " + std::to_string(count) + " triangles (" +
                   std::to_string(expected) + " bytes) but the file has " +
                   std::to_string(content.size()) + " bytes";
  } else {
    size_problem = "file too short for a binary STL (" + std::to_string(content.size()) +
                   " bytes, at least 84 needed)";
  }
  const std::string where =
      content.size() >= 84 ? "byte 80" : "byte " + std::to_string(content.size());
  if (!solid) throw ParseError(path, where, size_problem + " and it is not an ascii STL");
  // Starts with "solid" but does not have the binary size: ascii, unless it holds binary bytes.
  const std::string_view head = content.substr(0, 1024);
  for (char c : head)
    if (c == '\0' || (static_cast<unsigned char>(c) < 0x09))
      throw ParseError(path, "byte 80",
                       size_problem + " (the header starts with 'solid' but the data is binary)");
  mesh = AsciiStl(path, io_detail::strip_bom(content)).parse();
  if (mesh.faces.empty()) throw ParseError(path, "", "ascii STL contains no facets");
  return mesh;
}

}  // namespace meshdev
