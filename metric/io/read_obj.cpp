#include "metric/io/read_obj.h"

#include <omp.h>

#include <cassert>
#include <filesystem>
#include <iostream>
#include <limits>
#include <vector>

#include "metric/errors.h"
#include "metric/io/text_scan.h"

namespace meshdev {
namespace {

using io_detail::LineReader;
using io_detail::NumberStatus;
using io_detail::quoted;
using io_detail::Tokens;

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// Keywords of the OBJ specification that carry nothing a triangle mesh needs.
bool is_ignored_keyword(std::string_view k) {
  static constexpr std::string_view kIgnored[] = {
      "g",         "o",      "s",     "l",     "p",        "vp",       "mg",
      "usemap",    "maplib", "lod",   "bevel", "c_interp", "d_interp", "shadow_obj",
      "trace_obj", "cstype", "deg",   "bmat",  "step",     "curv",     "curv2",
      "surf",      "parm",   "trim",  "hole",  "scrv",     "sp",       "end",
      "con",       "ctech",  "stech", "call",  "csh"};
  for (std::string_view i : kIgnored)
    if (k == i) return true;
  return false;
}

// The polygons as read, before triangulation; indices already 0-based.
struct ObjPolygons {
  std::vector<std::uint32_t> v;       // one entry per corner
  std::vector<std::uint32_t> vt, vn;  // one per corner where the faces reference them, else empty
  std::vector<std::size_t> first;     // first corner of polygon i; first.back() = corners
};

// The three kinds of index a face corner holds.
enum IndexKind { kVertexIndex, kUvIndex, kNormalIndex };
constexpr const char* kIndexName[3] = {"vertex", "texture coordinate", "normal"};

class ObjParser {
 public:
  ObjParser(const std::string& path, std::string_view content) : path_(path), content_(content) {}

  // The whole file, line by line (the serial parse, and the chunked parse's oracle).
  TriMesh parse() {
    read_lines(0, io_detail::strip_bom(content_).size());
    return finish();
  }
  // One chunk of the chunked parse: the lines starting in [begin, end) (offsets into the text
  // without its byte order mark, at line starts), read as parse() reads them except that
  // relative indices are recorded to be resolved once the counts before the chunk are known
  // (merge). Throws ParseError where parse() would fail on these lines alone.
  void read_chunk(std::size_t begin, std::size_t end) {
    chunk_ = true;
    read_lines(begin, end);
  }
  // Appends the chunks read by read_chunk, in file order, to this (fresh) parser: their arrays
  // concatenated, their relative indices resolved. False where the chunks disagree in a way
  // parse() reports as an error (vertex colours on some vertices only, faces referencing
  // different attributes, a relative index before the first): the caller then runs parse() for
  // its message.
  bool merge(std::vector<ObjParser>& chunks);
  TriMesh finish();

 private:
  void read_lines(std::size_t begin, std::size_t end);
  [[noreturn]] void fail(const std::string& what) const {
    throw ParseError(path_, "line " + std::to_string(lines_.line_number()), what);
  }
  double number(std::string_view token) const {
    double value = 0;
    NumberStatus s = io_detail::parse_double(token, value);
    if (s != NumberStatus::kOk) fail(io_detail::describe_bad_number(token, s));
    return value;
  }
  void parse_vertex(Tokens& t);
  void parse_values(Tokens& t, std::vector<double>& out, int min_count, int max_count, int keep,
                    const char* what);
  void parse_face(Tokens& t);
  std::uint32_t resolve(std::string_view token, std::size_t count, IndexKind kind);
  void check_deferred(const std::vector<std::uint32_t>& ids, std::size_t count,
                      const char* what) const;
  // The line of polygon p: the p-th 'f' line (a face that does not parse ends the parse), found
  // by reading the text again, since only an error message needs it. O(file size).
  std::size_t line_of_polygon(std::size_t p) const;
  void build_channel(TriMesh& mesh, const std::vector<std::uint32_t>& ids,
                     const std::vector<double>& values, int dim, const char* name,
                     AttributeKind kind) const;
  void resolve_texture(TriMesh& mesh) const;

  const std::string& path_;
  std::string_view content_;
  LineReader lines_{""};
  std::vector<Vec3> positions_;
  std::vector<double> colors_;  // 3 per vertex when present
  std::vector<double> alpha_;
  int color_values_ = -1;  // values after x y z on the first v line: 0 (none), 1 (w), 3, 4
  std::vector<double> uvs_, normals_;
  ObjPolygons polys_;
  int face_has_vt_ = -1, face_has_vn_ = -1;  // -1 until the first face
  std::size_t first_face_line_ = 0;
  std::string mtllib_, material_;
  // Chunk mode: relative indices, each as the corner's position in its list (polys_.v, .vt or
  // .vn) and the index counted from the chunk's first element of its kind (negative: before it).
  struct Relative {
    std::size_t corner;
    std::int64_t local;
  };
  bool chunk_ = false;
  std::vector<Relative> relative_[3];
};

// Whether two first vertices' value counts after x y z agree (parse_vertex's rule: w or nothing
// are one class; r g b and r g b a are each their own).
bool same_color_class(int a, int b) {
  return a == b || (a <= 1 && b <= 1);
}

template <class T>
void append(std::vector<T>& to, const std::vector<T>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

bool ObjParser::merge(std::vector<ObjParser>& chunks) {
  std::size_t corners = 0, polygons = 0, vertices = 0;
  for (const ObjParser& c : chunks) {
    corners += c.polys_.v.size();
    polygons += c.polys_.first.size() - 1;
    vertices += c.positions_.size();
  }
  polys_.v.reserve(corners);
  polys_.first.reserve(polygons + 1);
  positions_.reserve(vertices);
  polys_.first.push_back(0);
  for (ObjParser& c : chunks) {
    assert(c.chunk_);
    if (c.color_values_ >= 0) {
      if (color_values_ < 0)
        color_values_ = c.color_values_;
      else if (!same_color_class(color_values_, c.color_values_))
        return false;
    }
    if (c.face_has_vt_ >= 0) {
      if (face_has_vt_ < 0)
        face_has_vt_ = c.face_has_vt_, face_has_vn_ = c.face_has_vn_;
      else if (c.face_has_vt_ != face_has_vt_ || c.face_has_vn_ != face_has_vn_)
        return false;
    }
    if (mtllib_.empty()) mtllib_ = c.mtllib_;
    if (material_.empty()) material_ = c.material_;
    const std::size_t before[3] = {positions_.size(), uvs_.size() / 2, normals_.size() / 3};
    std::vector<std::uint32_t>* lists[3] = {&polys_.v, &polys_.vt, &polys_.vn};
    const std::vector<std::uint32_t>* chunk_lists[3] = {&c.polys_.v, &c.polys_.vt, &c.polys_.vn};
    for (int k = 0; k < 3; ++k) {
      const std::size_t at = lists[k]->size();
      append(*lists[k], *chunk_lists[k]);
      for (const Relative& r : c.relative_[k]) {
        const std::int64_t index = static_cast<std::int64_t>(before[k]) + r.local;
        if (index < 0) return false;  // before the first (parse() names it)
        (*lists[k])[at + r.corner] = static_cast<std::uint32_t>(index);
      }
    }
    const std::size_t corner_base = polys_.first.back();
    for (std::size_t p = 1; p < c.polys_.first.size(); ++p)
      polys_.first.push_back(corner_base + c.polys_.first[p]);
    append(positions_, c.positions_);
    append(colors_, c.colors_);
    append(alpha_, c.alpha_);
    append(uvs_, c.uvs_);
    append(normals_, c.normals_);
  }
  return true;
}

void ObjParser::read_lines(std::size_t begin, std::size_t end) {
  lines_ = LineReader(io_detail::strip_bom(content_).substr(0, end), begin);
  polys_.first.push_back(0);
  std::string_view line;
  while (lines_.next(line)) {
    Tokens t(line);
    std::string_view key;
    if (!t.next(key) || key.front() == '#') continue;
    if (key == "v") {
      parse_vertex(t);
    } else if (key == "vt") {
      parse_values(t, uvs_, 1, 3, 2, "texture coordinate (vt)");
    } else if (key == "vn") {
      parse_values(t, normals_, 3, 3, 3, "normal (vn)");
    } else if (key == "f") {
      parse_face(t);
    } else if (key == "mtllib") {
      if (mtllib_.empty()) mtllib_ = std::string(t.rest());
    } else if (key == "usemtl") {
      if (material_.empty()) material_ = std::string(t.rest());
    } else if (!is_ignored_keyword(key)) {
      fail("unknown OBJ keyword " + quoted(key));
    }
  }
}

TriMesh ObjParser::finish() {
  if (positions_.empty()) throw ParseError(path_, "", "no vertices (no 'v' line)");

  // Positive indices may refer to vertices defined later in the file: check them now.
  check_deferred(polys_.v, positions_.size(), "vertex");
  check_deferred(polys_.vt, uvs_.size() / 2, "texture coordinate");
  check_deferred(polys_.vn, normals_.size() / 3, "normal");

  TriMesh mesh;
  mesh.source_file = path_;
  mesh.positions = std::move(positions_);
  const std::size_t polygons = polys_.first.size() - 1;
  mesh.source_polygons = polygons;
  mesh.faces.reserve(polys_.v.size() - 2 * polygons);
  for (std::size_t p = 0; p < polygons; ++p)
    for (std::size_t c = polys_.first[p] + 1; c + 1 < polys_.first[p + 1]; ++c)
      mesh.faces.push_back({polys_.v[polys_.first[p]], polys_.v[c], polys_.v[c + 1]});

  if (color_values_ >= 3) {
    AttributeChannel& ch = mesh.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3);
    ch.values = std::move(colors_);
  }
  if (color_values_ == 4) {
    AttributeChannel& ch =
        mesh.add_channel("alpha", AttributeKind::kScalar, Storage::kPerVertex, 1);
    ch.values = std::move(alpha_);
  }
  if (face_has_vt_ == 1)
    build_channel(mesh, polys_.vt, uvs_, 2, "texcoord", AttributeKind::kTexCoord);
  if (face_has_vn_ == 1)
    build_channel(mesh, polys_.vn, normals_, 3, "normal", AttributeKind::kNormal);
  resolve_texture(mesh);
  return mesh;
}

void ObjParser::parse_vertex(Tokens& t) {
  std::string_view tok[8];
  int n = 0;
  while (n < 8 && t.next(tok[n])) ++n;
  if (n == 8) fail("too many values on a 'v' line (expected x y z [w] or x y z r g b [a])");
  if (n < 3) fail("vertex needs 3 coordinates, found " + std::to_string(n));
  if (n == 5) fail("'v' line with 5 values (expected x y z [w] or x y z r g b [a])");
  positions_.push_back({number(tok[0]), number(tok[1]), number(tok[2])});
  const int extra = n == 4 ? 1 : n - 3;
  if (color_values_ < 0) color_values_ = extra;
  if (extra != color_values_ && !(extra <= 1 && color_values_ <= 1))
    fail("vertex " + std::to_string(positions_.size()) + " has " + std::to_string(extra) +
         " values after x y z but the first vertex has " + std::to_string(color_values_) +
         " (colours must be given for every vertex or none)");
  if (extra == 1) number(tok[3]);  // w: checked, not stored
  if (extra >= 3)
    for (int k = 3; k < 6; ++k) colors_.push_back(number(tok[k]));
  if (extra == 4) alpha_.push_back(number(tok[6]));
}

void ObjParser::parse_values(Tokens& t, std::vector<double>& out, int min_count, int max_count,
                             int keep, const char* what) {
  std::string_view tok;
  int n = 0;
  double v[3] = {0, 0, 0};
  while (t.next(tok)) {
    if (n == max_count) fail(std::string("too many values for a ") + what);
    v[n++] = number(tok);
  }
  if (n < min_count || n < keep)
    fail(std::string(what) + " needs " + std::to_string(keep) + " values, found " +
         std::to_string(n));
  out.insert(out.end(), v, v + keep);
}

std::uint32_t ObjParser::resolve(std::string_view token, std::size_t count, IndexKind kind) {
  const char* what = kIndexName[kind];
  std::int64_t i = 0;
  NumberStatus s = io_detail::parse_int(token, i);
  if (s == NumberStatus::kNotNumber)
    fail(std::string(what) + " index " + quoted(token) + " is not an integer");
  if (s != NumberStatus::kOk)
    fail(std::string(what) + " index " + quoted(token) + " is out of range");
  if (i == 0) fail(std::string(what) + " index 0 (OBJ indices start at 1)");
  if (i < 0 && chunk_) {  // resolved by merge(): the count before the chunk is not known yet
    const std::vector<std::uint32_t>& list =
        kind == kVertexIndex ? polys_.v : (kind == kUvIndex ? polys_.vt : polys_.vn);
    relative_[kind].push_back({list.size(), static_cast<std::int64_t>(count) + i});
    return 0;
  }
  if (i < 0) {
    // Relative: -1 is the last one defined so far.
    // Negated in unsigned arithmetic: -INT64_MIN overflows (found by fuzz_read_mesh).
    if (std::uint64_t{0} - static_cast<std::uint64_t>(i) > count)
      fail(std::string(what) + " index " + std::to_string(i) + " refers before the first (" +
           std::to_string(count) + " defined so far)");
    return static_cast<std::uint32_t>(static_cast<std::int64_t>(count) + i);
  }
  if (i > static_cast<std::int64_t>(kNone) - 1)
    fail(std::string(what) + " index " + std::to_string(i) + " is out of range");
  return static_cast<std::uint32_t>(i - 1);
}

void ObjParser::parse_face(Tokens& t) {
  std::string_view tok;
  std::size_t corners = 0;
  int has_vt = -1, has_vn = -1;
  while (t.next(tok)) {
    if (tok.front() == '#') break;
    std::size_t s1 = tok.find('/');
    std::string_view a = tok.substr(0, s1), b, c;
    bool slash_vt = false, slash_vn = false;
    if (s1 != std::string_view::npos) {
      std::size_t s2 = tok.find('/', s1 + 1);
      b = tok.substr(s1 + 1, s2 == std::string_view::npos ? std::string_view::npos : s2 - s1 - 1);
      slash_vt = !b.empty();
      if (s2 != std::string_view::npos) {
        c = tok.substr(s2 + 1);
        if (c.find('/') != std::string_view::npos) fail("bad face corner " + quoted(tok));
        if (c.empty()) fail("bad face corner " + quoted(tok) + " (empty normal index)");
        slash_vn = true;
      }
    }
    if (a.empty()) fail("bad face corner " + quoted(tok) + " (no vertex index)");
    int vt_here = slash_vt ? 1 : 0, vn_here = slash_vn ? 1 : 0;
    if (has_vt < 0) has_vt = vt_here, has_vn = vn_here;
    if (vt_here != has_vt || vn_here != has_vn)
      fail("face corners " + std::to_string(corners + 1) +
           " and 1 differ in which of vt/vn they reference (" + quoted(tok) + ")");
    polys_.v.push_back(resolve(a, positions_.size(), kVertexIndex));
    // (Every face references vt and vn as the first one does, or the parse fails below: so vt
    // and vn end up with an entry per corner or none.)
    if (slash_vt) polys_.vt.push_back(resolve(b, uvs_.size() / 2, kUvIndex));
    if (slash_vn) polys_.vn.push_back(resolve(c, normals_.size() / 3, kNormalIndex));
    ++corners;
  }
  if (corners < 3) {
    polys_.v.resize(polys_.first.back());
    fail("face with " + std::to_string(corners) + " corners (at least 3 needed)");
  }
  if (face_has_vt_ < 0) {
    face_has_vt_ = has_vt, face_has_vn_ = has_vn;
    first_face_line_ = lines_.line_number();
  }
  if (has_vt != face_has_vt_ || has_vn != face_has_vn_)
    fail(std::string("face ") + (has_vt != face_has_vt_ ? "texture coordinates" : "normals") +
         (has_vt != face_has_vt_ ? (has_vt ? " present" : " missing")
                                 : (has_vn ? " present" : " missing")) +
         " but not so on the first face (line " + std::to_string(first_face_line_) +
         "); every face must reference the same attributes");
  polys_.first.push_back(polys_.v.size());
}

std::size_t ObjParser::line_of_polygon(std::size_t p) const {
  LineReader lines(io_detail::strip_bom(content_));
  std::string_view line;
  std::size_t faces = 0;
  while (lines.next(line)) {
    Tokens t(line);
    std::string_view key;
    if (t.next(key) && key == "f" && faces++ == p) return lines.line_number();
  }
  assert(false && "fewer 'f' lines than polygons");
  return 0;
}

void ObjParser::check_deferred(const std::vector<std::uint32_t>& ids, std::size_t count,
                               const char* what) const {
  if (ids.empty()) return;  // (the faces do not reference these)
  assert(ids.size() == polys_.v.size());
  for (std::size_t p = 0; p + 1 < polys_.first.size(); ++p)
    for (std::size_t c = polys_.first[p]; c < polys_.first[p + 1]; ++c)
      if (ids[c] >= count)
        throw ParseError(path_, "line " + std::to_string(line_of_polygon(p)),
                         std::string(what) + " index " + std::to_string(ids[c] + 1ull) +
                             " out of range (" + std::to_string(count) + " defined)");
}

// Per vertex when every vertex is used and every corner of vertex v names the same vt/vn;
// otherwise per corner, following the fan triangulation.
void ObjParser::build_channel(TriMesh& mesh, const std::vector<std::uint32_t>& ids,
                              const std::vector<double>& values, int dim, const char* name,
                              AttributeKind kind) const {
  const std::size_t d = static_cast<std::size_t>(dim);
  std::vector<std::uint32_t> of_vertex(mesh.positions.size(), kNone);
  bool per_vertex = true;
  for (std::size_t c = 0; c < ids.size() && per_vertex; ++c) {
    std::uint32_t& slot = of_vertex[polys_.v[c]];
    if (slot == kNone) slot = ids[c];
    per_vertex = slot == ids[c];
  }
  for (std::size_t v = 0; v < of_vertex.size() && per_vertex; ++v)
    per_vertex = of_vertex[v] != kNone;
  if (per_vertex) {
    AttributeChannel& ch = mesh.add_channel(name, kind, Storage::kPerVertex, dim);
    for (std::size_t v = 0; v < of_vertex.size(); ++v)
      for (std::size_t k = 0; k < d; ++k) ch.values[v * d + k] = values[of_vertex[v] * d + k];
    return;
  }
  AttributeChannel& ch = mesh.add_channel(name, kind, Storage::kPerCorner, dim);
  std::size_t f = 0;
  for (std::size_t p = 0; p + 1 < polys_.first.size(); ++p) {
    const std::size_t c0 = polys_.first[p];
    for (std::size_t c = c0 + 1; c + 1 < polys_.first[p + 1]; ++c, ++f) {
      const std::size_t corner[3] = {c0, c, c + 1};
      for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t k = 0; k < d; ++k)
          ch.values[(3 * f + i) * d + k] = values[ids[corner[i]] * d + k];
    }
  }
}

// Skips map_Kd options (-s u v w, -blendu on, ...) and returns the file name.
std::string_view map_file_name(std::string_view rest) {
  Tokens t(rest);
  std::string_view tok;
  while (true) {
    Tokens probe = t;
    if (!probe.next(tok) || tok.front() != '-') break;
    t.next(tok);
    int args = 1;
    if (tok == "-s" || tok == "-o" || tok == "-t")
      args = 3;
    else if (tok == "-mm")
      args = 2;
    for (int i = 0; i < args; ++i) t.next(tok);
  }
  return t.rest();
}

void ObjParser::resolve_texture(TriMesh& mesh) const {
  if (mtllib_.empty()) return;
  const std::string folder = io_detail::folder_of(path_);
  std::string mtl_path = io_detail::resolve_relative(folder, mtllib_);
  std::string mtl;
  try {
    // Only a regular file: "mtllib /dev/zero" (or a FIFO) would otherwise read without end.
    std::error_code ec;
    if (std::filesystem::exists(mtl_path, ec) && !std::filesystem::is_regular_file(mtl_path, ec))
      throw IoError(mtl_path + ": not a regular file");
    mtl = io_detail::read_file_bytes(mtl_path);
  } catch (const IoError& e) {
    std::cerr << "meshdev: warning: " << path_ << ": mtllib " << quoted(mtllib_)
              << " not readable (" << e.what() << "); no texture\n";
    return;
  }
  LineReader lines(io_detail::strip_bom(mtl));
  std::string_view line, current, first_map;
  bool wanted = false;
  while (lines.next(line)) {
    Tokens t(line);
    std::string_view key;
    if (!t.next(key)) continue;
    if (key == "newmtl") {
      current = t.rest();
      wanted = !material_.empty() && current == material_;
    } else if (key == "map_Kd") {
      std::string_view file = map_file_name(t.rest());
      if (file.empty()) continue;
      if (wanted) {
        mesh.texture_file = io_detail::resolve_relative(folder, file);
        return;
      }
      if (first_map.empty()) first_map = file;
    }
  }
  // No usemtl (or its material has no map_Kd): fall back to the first map_Kd of the library.
  if (!first_map.empty() && material_.empty())
    mesh.texture_file = io_detail::resolve_relative(folder, first_map);
}

}  // namespace

namespace detail {

TriMesh read_obj_in_chunks(const std::string& path, std::string_view content, int chunks,
                           int threads, bool* used_chunks) {
  if (used_chunks != nullptr) *used_chunks = false;
  const std::string_view text = io_detail::strip_bom(content);
  const std::vector<std::size_t> start = io_detail::line_chunks(text, 0, chunks);
  const auto n = static_cast<std::int64_t>(start.size() - 1);
  std::vector<ObjParser> parts(static_cast<std::size_t>(n), ObjParser(path, content));
  bool failed = false;
  const int team = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel for num_threads(team) schedule(dynamic, 1) reduction(|| : failed)
  for (std::int64_t k = 0; k < n; ++k) {
    try {
      parts[static_cast<std::size_t>(k)].read_chunk(start[k], start[k + 1]);
    } catch (...) {   // (no exception may leave the parallel region)
      failed = true;  // parse() below finds the first error and names its line
    }
  }
  ObjParser whole(path, content);
  if (failed || !whole.merge(parts)) return ObjParser(path, content).parse();
  parts.clear();
  TriMesh mesh = whole.finish();
  if (used_chunks != nullptr) *used_chunks = true;
  return mesh;
}

}  // namespace detail

TriMesh read_obj(const std::string& path, std::string_view content, int threads) {
  const int chunks = io_detail::chunks_for(content.size(), threads);
  if (chunks == 1) return ObjParser(path, content).parse();
  return detail::read_obj_in_chunks(path, content, chunks, threads);
}

}  // namespace meshdev
