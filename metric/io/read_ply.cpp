#include "metric/io/read_ply.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
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

constexpr std::size_t kMaxHeaderBytes = 64 * 1024;

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };
enum class Format { kAscii, kBinaryLE, kBinaryBE };

bool parse_type(std::string_view s, PlyType& t) {
  struct Name {
    std::string_view name;
    PlyType type;
  };
  static constexpr Name kNames[] = {
      {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},       {"uchar", PlyType::kUint8},
      {"uint8", PlyType::kUint8},    {"short", PlyType::kInt16},     {"int16", PlyType::kInt16},
      {"ushort", PlyType::kUint16},  {"uint16", PlyType::kUint16},   {"int", PlyType::kInt32},
      {"int32", PlyType::kInt32},    {"uint", PlyType::kUint32},     {"uint32", PlyType::kUint32},
      {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32}, {"double", PlyType::kFloat64},
      {"float64", PlyType::kFloat64}};
  for (const Name& n : kNames)
    if (s == n.name) {
      t = n.type;
      return true;
    }
  return false;
}

std::size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 0;
}

bool is_float(PlyType t) {
  return t == PlyType::kFloat32 || t == PlyType::kFloat64;
}

// Divisor mapping an integer colour to [0, 1]; floats are taken as they are.
double color_scale(PlyType t) {
  if (is_float(t)) return 1.0;
  return t == PlyType::kUint16 ? 65535.0 : 255.0;
}

void integer_range(PlyType t, std::int64_t& lo, std::int64_t& hi) {
  switch (t) {
    case PlyType::kInt8:
      lo = -128, hi = 127;
      return;
    case PlyType::kUint8:
      lo = 0, hi = 255;
      return;
    case PlyType::kInt16:
      lo = -32768, hi = 32767;
      return;
    case PlyType::kUint16:
      lo = 0, hi = 65535;
      return;
    case PlyType::kInt32:
      lo = std::numeric_limits<std::int32_t>::min(), hi = std::numeric_limits<std::int32_t>::max();
      return;
    case PlyType::kUint32:
      lo = 0, hi = std::numeric_limits<std::uint32_t>::max();
      return;
    default:
      lo = hi = 0;
      return;
  }
}

// Where a property's values go.
enum class Target {
  kSkip,
  kX,
  kY,
  kZ,
  kNormal,  // component `index`
  kColor,   // component `index`
  kAlpha,
  kTexCoord,  // component `index`
  kScalar,    // channel `index` of the element
  kIndices,   // face list
  kCornerUV,  // face texcoord list
};

struct Property {
  std::string name;
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;
  PlyType type = PlyType::kFloat32;
  Target target = Target::kSkip;
  int index = 0;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> props;
  std::size_t line = 0;
};

struct Header {
  Format format = Format::kAscii;
  std::vector<Element> elements;
  std::size_t body = 0;       // byte offset of the first data byte
  std::size_t body_line = 0;  // line number of the first data line (ascii)
  std::string texture_file;
};

// A decoded value: integers exactly, floats as double.
struct Value {
  double d = 0;
  std::int64_t i = 0;
};

// The channels being filled, in the order they will be added to the mesh.
struct ScalarOut {
  std::string name;
  AttributeKind kind = AttributeKind::kScalar;
  int dim = 1;
  double scale = 1.0;
  std::vector<double> values;
};

// The binary value of type `t` at `at` (byte-swapped first if `swap`): integers exactly, floats
// as double. Each case copies a fixed size, so the compiler turns it into one load.
template <class T>
T load_binary(const char* at, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, at, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T x;
  std::memcpy(&x, b, sizeof(T));
  return x;
}
[[gnu::always_inline]] inline Value decode_binary(PlyType t, const char* at, bool swap) {
  Value v;
  switch (t) {
    case PlyType::kInt8:
      v.i = load_binary<std::int8_t>(at, swap);
      break;
    case PlyType::kUint8:
      v.i = load_binary<std::uint8_t>(at, swap);
      break;
    case PlyType::kInt16:
      v.i = load_binary<std::int16_t>(at, swap);
      break;
    case PlyType::kUint16:
      v.i = load_binary<std::uint16_t>(at, swap);
      break;
    case PlyType::kInt32:
      v.i = load_binary<std::int32_t>(at, swap);
      break;
    case PlyType::kUint32:
      v.i = load_binary<std::uint32_t>(at, swap);
      break;
    case PlyType::kFloat32:
      v.d = load_binary<float>(at, swap);
      return v;
    case PlyType::kFloat64:
      v.d = load_binary<double>(at, swap);
      return v;
  }
  v.d = static_cast<double>(v.i);
  return v;
}

class PlyParser {
 public:
  PlyParser(const std::string& path, std::string_view content) : path_(path), data_(content) {}
  TriMesh parse();

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw ParseError(path_, where, what);
  }
  static std::string line_at(std::size_t n) { return "line " + std::to_string(n); }
  std::string where_now() const {
    return header_.format == Format::kAscii ? line_at(lines_.line_number())
                                            : "byte " + std::to_string(pos_);
  }
  void parse_header();
  void plan_vertex(Element& e);
  void plan_face(Element& e);
  void read_body();
  void read_element(Element& e);
  // Binary fast path: reads the leading records of e that are well formed, for the two layouts
  // nearly every binary file has (a vertex element of scalar properties; a face element holding
  // only its vertex_indices list), and returns how many it read. The generic loop of
  // read_element goes on from there, so a malformed record is reported by the same code, with
  // the same message, whichever path met it first. 0 for other elements.
  std::uint64_t read_binary_records(const Element& e, bool is_vertex, bool is_face);
  // read_binary_records for a face element of one index list: count_at and item_at decode the
  // list count and an index at a byte address.
  template <class CountAt, class ItemAt>
  std::uint64_t read_index_lists(const Element& e, std::uint64_t first_record, CountAt count_at,
                                 ItemAt item_at);
  // read_binary_records for face records of the commonest layout (a uchar count, int or uint
  // indices, the host's byte order) while they are triangles: each goes straight into
  // triangles_, the mesh's faces as they will be, without corner lists, offsets or a fan pass.
  // Returns how many it read; the caller hands the rest to read_index_lists.
  std::uint64_t read_triangle_records(const Element& e, bool signed_indices);
  // Stores the finite value d of scalar property p of vertex i.
  void store_vertex_value(const Property& p, std::size_t i, double d);

  // Value sources.
  void begin_record(const Element& e, std::uint64_t r);
  // The next value of type t (property `prop` of record r of e). Binary values with enough data
  // left are decoded here, inline in the record loop; ascii values and the truncation error out
  // of line.
  Value read_value(PlyType t, const Element& e, std::uint64_t r, const std::string& prop) {
    if (header_.format != Format::kAscii) {
      const std::size_t n = type_size(t);
      if (data_.size() - pos_ >= n) {
        const Value v = decode_binary(t, data_.data() + pos_, swap_);
        pos_ += n;
        return v;
      }
    }
    return read_value_slow(t, e, r, prop);
  }
  Value read_value_slow(PlyType t, const Element& e, std::uint64_t r, const std::string& prop);
  void end_record(const Element& e, std::uint64_t r);

  std::string element_ref(const Element& e, std::uint64_t r) const {
    return e.name + " " + std::to_string(r);
  }

  const std::string& path_;
  std::string_view data_;
  Header header_;
  bool little_host_ = true;
  bool swap_ = false;  // binary data in the other byte order than the host's
  // ascii state
  LineReader lines_{""};
  Tokens tokens_{""};
  // binary state
  std::size_t pos_ = 0;

  // Results.
  std::vector<Vec3> positions_;
  std::vector<ScalarOut> vertex_out_;  // normal, color, alpha, texcoord, scalars (by index)
  std::vector<ScalarOut> face_out_;
  int normal_out_ = -1, color_out_ = -1, alpha_out_ = -1, uv_out_ = -1;
  int face_color_out_ = -1, face_alpha_out_ = -1;
  std::vector<std::uint32_t> corners_;
  std::vector<std::size_t> first_ = {0};
  // Faces read by read_triangle_records; while faces_are_triangles_, they are all the faces read
  // (corners_ and first_ stay empty), else they have been moved into corners_ and first_.
  std::vector<Triangle> triangles_;
  bool faces_are_triangles_ = false;
  std::vector<double> corner_uv_;
  bool has_corner_uv_ = false;
  std::uint64_t vertex_count_ = 0;
  bool have_vertex_ = false;
  const Element* face_element_ = nullptr;
};

void PlyParser::parse_header() {
  std::string_view text = io_detail::strip_bom(data_);
  const std::size_t bom = data_.size() - text.size();
  LineReader lines(text);
  std::string_view line;
  if (!lines.next(line) || io_detail::trim(line) != "ply")
    fail("line 1", "not a PLY file (no 'ply' magic line)");
  bool have_format = false, done = false;
  while (lines.next(line)) {
    const std::size_t n = lines.line_number();
    if (lines.offset() > kMaxHeaderBytes + 1 && !done)
      fail(line_at(n), "no 'end_header' within the first 64 KiB");
    Tokens t(line);
    std::string_view key;
    if (!t.next(key)) continue;
    if (key == "comment") {
      Tokens c(t.rest());
      std::string_view word;
      if (c.next(word) && word == "TextureFile") header_.texture_file = std::string(c.rest());
    } else if (key == "obj_info") {
    } else if (key == "format") {
      std::string_view f, version;
      if (have_format) fail(line_at(n), "second 'format' line");
      if (!t.next(f) || !t.next(version) || !t.empty_rest())
        fail(line_at(n), "malformed format line (expected 'format <type> 1.0')");
      if (f == "ascii")
        header_.format = Format::kAscii;
      else if (f == "binary_little_endian")
        header_.format = Format::kBinaryLE;
      else if (f == "binary_big_endian")
        header_.format = Format::kBinaryBE;
      else
        fail(line_at(n), "unknown PLY format " + quoted(f));
      if (version != "1.0" && version != "1")
        fail(line_at(n), "unsupported PLY version " + quoted(version));
      have_format = true;
    } else if (key == "element") {
      std::string_view name, count;
      if (!have_format) fail(line_at(n), "'element' before 'format'");
      if (!t.next(name) || !t.next(count) || !t.empty_rest())
        fail(line_at(n), "malformed element line (expected 'element <name> <count>')");
      std::int64_t c = 0;
      if (io_detail::parse_int(count, c) != NumberStatus::kOk || c < 0)
        fail(line_at(n), "element " + quoted(name) + " has a bad count " + quoted(count));
      for (const Element& e : header_.elements)
        if (e.name == name) fail(line_at(n), "element " + quoted(name) + " declared twice");
      header_.elements.push_back({std::string(name), static_cast<std::uint64_t>(c), {}, n});
    } else if (key == "property") {
      if (header_.elements.empty()) fail(line_at(n), "'property' before any 'element'");
      Property p;
      std::string_view type, name;
      if (!t.next(type)) fail(line_at(n), "malformed property line");
      if (type == "list") {
        std::string_view ct, it;
        if (!t.next(ct) || !t.next(it))
          fail(
              line_at(n),
              "malformed list property (expected 'property list <count type> <item type> <name>')");
        if (!parse_type(ct, p.count_type)) fail(line_at(n), "unknown PLY type " + quoted(ct));
        if (!parse_type(it, p.type)) fail(line_at(n), "unknown PLY type " + quoted(it));
        if (is_float(p.count_type))
          fail(line_at(n), "list count type " + quoted(ct) + " is not an integer type");
        p.is_list = true;
      } else if (!parse_type(type, p.type)) {
        fail(line_at(n), "unknown PLY type " + quoted(type));
      }
      if (!t.next(name) || !t.empty_rest())
        fail(line_at(n), "malformed property line (expected one name after the type)");
      p.name = std::string(name);
      for (const Property& q : header_.elements.back().props)
        if (q.name == p.name) fail(line_at(n), "property " + quoted(name) + " declared twice");
      header_.elements.back().props.push_back(std::move(p));
    } else if (key == "end_header") {
      if (!t.empty_rest()) fail(line_at(n), "text after end_header");
      done = true;
      break;
    } else {
      fail(line_at(n), "unknown PLY header keyword " + quoted(key));
    }
  }
  if (!done) {
    if (lines.offset() > kMaxHeaderBytes) fail("", "no 'end_header' within the first 64 KiB");
    fail("", "header has no 'end_header' line (file ends inside the header)");
  }
  if (!have_format) fail("", "header has no 'format' line");
  header_.body = bom + lines.offset();
  if (header_.body > data_.size()) header_.body = data_.size();
  header_.body_line = lines.line_number() + 1;
}

void PlyParser::plan_vertex(Element& e) {
  auto find = [&e](std::string_view name) -> Property* {
    for (Property& p : e.props)
      if (!p.is_list && p.name == name) return &p;
    return nullptr;
  };
  Property* xyz[3] = {find("x"), find("y"), find("z")};
  for (int k = 0; k < 3; ++k)
    if (!xyz[k])
      fail(line_at(e.line),
           std::string("vertex element has no scalar property '") + "xyz"[k] + "'");
  xyz[0]->target = Target::kX, xyz[1]->target = Target::kY, xyz[2]->target = Target::kZ;

  auto add = [this](std::string name, AttributeKind kind, int dim, double scale) {
    vertex_out_.push_back({std::move(name), kind, dim, scale, {}});
    return static_cast<int>(vertex_out_.size() - 1);
  };
  Property* n[3] = {find("nx"), find("ny"), find("nz")};
  if (n[0] && n[1] && n[2]) {
    normal_out_ = add("normal", AttributeKind::kNormal, 3, 1.0);
    for (int k = 0; k < 3; ++k) n[k]->target = Target::kNormal, n[k]->index = k;
  }
  Property* c[3] = {find("red"), find("green"), find("blue")};
  if (!(c[0] && c[1] && c[2]))
    c[0] = find("diffuse_red"), c[1] = find("diffuse_green"), c[2] = find("diffuse_blue");
  if (c[0] && c[1] && c[2]) {
    if (c[0]->type != c[1]->type || c[0]->type != c[2]->type)
      fail(line_at(e.line), "colour properties red/green/blue have different types");
    color_out_ = add("color", AttributeKind::kColor, 3, color_scale(c[0]->type));
    for (int k = 0; k < 3; ++k) c[k]->target = Target::kColor, c[k]->index = k;
    Property* a = find("alpha");
    if (!a) a = find("diffuse_alpha");
    if (a) {
      alpha_out_ = add("alpha", AttributeKind::kScalar, 1, color_scale(a->type));
      a->target = Target::kAlpha;
    }
  }
  static constexpr std::string_view kUV[][2] = {
      {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
  for (const auto& names : kUV) {
    Property* u = find(names[0]);
    Property* v = find(names[1]);
    if (u && v && u->target == Target::kSkip && v->target == Target::kSkip) {
      uv_out_ = add("texcoord", AttributeKind::kTexCoord, 2, 1.0);
      u->target = v->target = Target::kTexCoord;
      v->index = 1;
      break;
    }
  }
  for (Property& p : e.props) {
    if (p.is_list || p.target != Target::kSkip) continue;
    std::string name = p.name;
    for (const ScalarOut& o : vertex_out_)
      if (o.name == name) name = "vertex_" + name;
    p.target = Target::kScalar;
    p.index = add(name, AttributeKind::kScalar, 1, 1.0);
  }
}

void PlyParser::plan_face(Element& e) {
  auto taken = [this](const std::string& name) {
    for (const ScalarOut& o : vertex_out_)
      if (o.name == name) return true;
    for (const ScalarOut& o : face_out_)
      if (o.name == name) return true;
    return false;
  };
  auto add = [&](std::string name, AttributeKind kind, int dim, double scale) {
    if (taken(name)) name = "face_" + name;
    face_out_.push_back({std::move(name), kind, dim, scale, {}});
    return static_cast<int>(face_out_.size() - 1);
  };
  Property* indices = nullptr;
  for (Property& p : e.props)
    if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index") && !indices)
      indices = &p;
  if (!indices && e.count > 0)
    fail(line_at(e.line), "face element has no list property 'vertex_indices'");
  if (!indices) return;
  if (is_float(indices->type))
    fail(line_at(e.line), "face vertex_indices has a floating-point item type (integers needed)");
  indices->target = Target::kIndices;
  for (Property& p : e.props)
    if (p.is_list && p.name == "texcoord" && p.target == Target::kSkip) {
      p.target = Target::kCornerUV;
      has_corner_uv_ = true;
      // Both per-vertex and per-corner UVs: the per-corner ones are "texcoord".
      if (uv_out_ >= 0) vertex_out_[uv_out_].name = "vertex_texcoord";
    }
  auto find = [&e](std::string_view name) -> Property* {
    for (Property& p : e.props)
      if (!p.is_list && p.name == name) return &p;
    return nullptr;
  };
  Property* c[3] = {find("red"), find("green"), find("blue")};
  if (c[0] && c[1] && c[2] && c[0]->type == c[1]->type && c[0]->type == c[2]->type) {
    face_color_out_ = add("color", AttributeKind::kColor, 3, color_scale(c[0]->type));
    for (int k = 0; k < 3; ++k) c[k]->target = Target::kColor, c[k]->index = k;
    if (Property* a = find("alpha")) {
      face_alpha_out_ = add("alpha", AttributeKind::kScalar, 1, color_scale(a->type));
      a->target = Target::kAlpha;
    }
  }
  for (Property& p : e.props) {
    if (p.is_list || p.target != Target::kSkip) continue;
    p.target = Target::kScalar;
    p.index = add(p.name, AttributeKind::kScalar, 1, 1.0);
  }
}

// Smallest number of bytes (binary) or characters (ascii) one record of `e` can take.
std::uint64_t min_record_size(const Element& e, Format f) {
  std::uint64_t size = 0;
  for (const Property& p : e.props)
    size += f == Format::kAscii ? 2 : type_size(p.is_list ? p.count_type : p.type);
  return size;
}

void PlyParser::begin_record(const Element& e, std::uint64_t r) {
  if (header_.format != Format::kAscii) return;
  std::string_view line;
  do {
    if (!lines_.next(line))
      fail(line_at(lines_.line_number() + 1), "file ends after " + std::to_string(r) + " of " +
                                                  std::to_string(e.count) + " " + e.name +
                                                  " records (header count larger than the data)");
  } while (io_detail::trim(line).empty());
  tokens_ = Tokens(line);
}

void PlyParser::end_record(const Element& e, std::uint64_t r) {
  if (header_.format != Format::kAscii) return;
  std::string_view extra;
  if (tokens_.next(extra))
    fail(where_now(),
         element_ref(e, r) + ": extra value " + quoted(extra) + " after the declared properties");
}

Value PlyParser::read_value_slow(PlyType t, const Element& e, std::uint64_t r,
                                 const std::string& prop) {
  Value v;
  if (header_.format == Format::kAscii) {
    std::string_view tok;
    if (!tokens_.next(tok))
      fail(where_now(), element_ref(e, r) + ": missing value for property '" + prop + "'");
    if (is_float(t)) {
      NumberStatus s = io_detail::parse_double(tok, v.d);
      if (s != NumberStatus::kOk)
        fail(where_now(),
             element_ref(e, r) + " " + prop + ": " + io_detail::describe_bad_number(tok, s));
      return v;
    }
    NumberStatus s = io_detail::parse_int(tok, v.i);
    std::int64_t lo = 0, hi = 0;
    integer_range(t, lo, hi);
    if (s == NumberStatus::kNotNumber)
      fail(where_now(), element_ref(e, r) + " " + prop + ": " + quoted(tok) + " is not an integer");
    if (s != NumberStatus::kOk || v.i < lo || v.i > hi)
      fail(where_now(),
           element_ref(e, r) + " " + prop + ": " + quoted(tok) + " is out of range for its type");
    v.d = static_cast<double>(v.i);
    return v;
  }
  // Binary: read_value comes here only when fewer than the value's bytes are left.
  assert(data_.size() - pos_ < type_size(t));
  fail("byte " + std::to_string(pos_), element_ref(e, r) + ": file ends inside property '" + prop +
                                           "' (truncated; header counts larger than the data?)");
}

void PlyParser::store_vertex_value(const Property& p, std::size_t i, double d) {
  switch (p.target) {
    case Target::kX:
      positions_[i].x = d;
      break;
    case Target::kY:
      positions_[i].y = d;
      break;
    case Target::kZ:
      positions_[i].z = d;
      break;
    case Target::kNormal:
      vertex_out_[normal_out_].values[3 * i + p.index] = d;
      break;
    case Target::kColor:
      vertex_out_[color_out_].values[3 * i + p.index] = d / vertex_out_[color_out_].scale;
      break;
    case Target::kAlpha:
      vertex_out_[alpha_out_].values[i] = d / vertex_out_[alpha_out_].scale;
      break;
    case Target::kTexCoord:
      vertex_out_[uv_out_].values[2 * i + p.index] = d;
      break;
    case Target::kScalar:
      vertex_out_[p.index].values[i] = d;
      break;
    default:
      break;
  }
}

std::uint64_t PlyParser::read_binary_records(const Element& e, bool is_vertex, bool is_face) {
  const char* const data = data_.data();
  const std::size_t size = data_.size();
  if (is_vertex) {
    for (const Property& p : e.props)
      if (p.is_list) return 0;
    const std::uint64_t record = min_record_size(e, header_.format);  // fixed: no lists
    const std::uint64_t whole = std::min<std::uint64_t>(e.count, (size - pos_) / record);
    // The commonest layout, float x, y, z first in the host's byte order, loaded at once.
    auto is_float = [&](std::size_t k, Target t) {
      return e.props[k].type == PlyType::kFloat32 && e.props[k].target == t;
    };
    const std::size_t skip = !swap_ && e.props.size() >= 3 && is_float(0, Target::kX) &&
                                     is_float(1, Target::kY) && is_float(2, Target::kZ)
                                 ? 3
                                 : 0;
    for (std::uint64_t r = 0; r < whole; ++r, pos_ += record) {
      std::size_t at = pos_;
      if (skip == 3) {
        float xyz[3];
        std::memcpy(xyz, data + at, sizeof xyz);
        if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) return r;
        positions_[r] = {xyz[0], xyz[1], xyz[2]};
        at += sizeof xyz;
      }
      for (std::size_t k = skip; k < e.props.size(); ++k) {
        const Property& p = e.props[k];
        const double d = decode_binary(p.type, data + at, swap_).d;
        at += type_size(p.type);
        if (p.target == Target::kSkip) continue;
        if (!std::isfinite(d)) return r;  // the generic loop reports it
        store_vertex_value(p, static_cast<std::size_t>(r), d);
      }
    }
    return whole;
  }
  if (!is_face || e.props.size() != 1 || e.props[0].target != Target::kIndices) return 0;
  const Property& p = e.props[0];
  const bool common = !swap_ && p.count_type == PlyType::kUint8 &&
                      (p.type == PlyType::kInt32 || p.type == PlyType::kUint32);
  std::uint64_t done = 0;
  if (common && first_.size() == 1) {
    faces_are_triangles_ = true;
    done = read_triangle_records(e, p.type == PlyType::kInt32);
    if (done == e.count) return done;
    // A polygon or a bad record: the triangles become corner lists, and the rest goes on below.
    faces_are_triangles_ = false;
    for (const Triangle& t : triangles_) {
      corners_.insert(corners_.end(), t.begin(), t.end());
      first_.push_back(corners_.size());
    }
    triangles_ = {};
  }
  // The common layouts with the types fixed at compile time; any other through decode_binary.
  if (common && p.type == PlyType::kInt32)
    return read_index_lists(
        e, done, [](const char* at) { return load_binary<std::uint8_t>(at, false); },
        [](const char* at) { return load_binary<std::int32_t>(at, false); });
  if (common)
    return read_index_lists(
        e, done, [](const char* at) { return load_binary<std::uint8_t>(at, false); },
        [](const char* at) { return load_binary<std::uint32_t>(at, false); });
  return read_index_lists(
      e, done, [&](const char* at) { return decode_binary(p.count_type, at, swap_).i; },
      [&](const char* at) { return decode_binary(p.type, at, swap_).i; });
}

std::uint64_t PlyParser::read_triangle_records(const Element& e, bool signed_indices) {
  constexpr std::size_t kRecord = 1 + 3 * sizeof(std::uint32_t);
  const std::uint64_t whole = std::min<std::uint64_t>(e.count, (data_.size() - pos_) / kRecord);
  // Indices read as unsigned: a negative int32 has its top bit set, refused below.
  const std::uint32_t limit = signed_indices ? static_cast<std::uint32_t>(std::min<std::uint64_t>(
                                                   vertex_count_, std::uint64_t{1} << 31))
                                             : static_cast<std::uint32_t>(vertex_count_);
  triangles_.reserve(e.count);
  const char* at = data_.data() + pos_;
  std::uint64_t r = 0;
  for (; r < whole; ++r, at += kRecord) {
    if (static_cast<unsigned char>(*at) != 3) break;
    Triangle t;
    std::memcpy(t.data(), at + 1, sizeof t);
    if (t[0] >= limit || t[1] >= limit || t[2] >= limit) break;
    triangles_.push_back(t);
  }
  pos_ = static_cast<std::size_t>(at - data_.data());
  return r;
}

template <class CountAt, class ItemAt>
std::uint64_t PlyParser::read_index_lists(const Element& e, std::uint64_t first_record,
                                          CountAt count_at, ItemAt item_at) {
  const Property& p = e.props[0];
  const char* const data = data_.data();
  const std::size_t size = data_.size();
  const std::size_t count_size = type_size(p.count_type), item_size = type_size(p.type);
  for (std::uint64_t r = first_record; r < e.count; ++r) {
    if (size - pos_ < count_size) return r;
    const auto n = static_cast<std::int64_t>(count_at(data + pos_));
    if (n < 3 || static_cast<std::uint64_t>(n) > (size - pos_ - count_size) / item_size) return r;
    const char* items = data + pos_ + count_size;
    for (std::int64_t k = 0; k < n; ++k, items += item_size) {
      const auto v = static_cast<std::int64_t>(item_at(items));
      if (v < 0 || static_cast<std::uint64_t>(v) >= vertex_count_) {
        corners_.resize(first_.back());  // this record again, by the generic loop
        return r;
      }
      corners_.push_back(static_cast<std::uint32_t>(v));
    }
    pos_ = static_cast<std::size_t>(items - data);
    first_.push_back(corners_.size());
  }
  return e.count;
}

void PlyParser::read_element(Element& e) {
  const bool is_vertex = e.name == "vertex";
  const bool is_face = &e == face_element_;
  const std::uint64_t min_size = min_record_size(e, header_.format);
  const std::uint64_t available =
      data_.size() - (header_.format == Format::kAscii ? lines_.offset() : pos_);
  if (e.count > 0 && e.props.empty())
    fail(line_at(e.line), "element '" + e.name + "' has records but no properties");
  if (e.count > 0 && e.count > (available + 1) / min_size)
    fail(line_at(e.line), "element '" + e.name + "' declares " + std::to_string(e.count) +
                              " records but only " + std::to_string(available) +
                              " bytes of data remain (at least " + std::to_string(min_size) +
                              " needed per record)");
  if (is_vertex) {
    positions_.resize(e.count);
    for (ScalarOut& o : vertex_out_) o.values.resize(e.count * static_cast<std::size_t>(o.dim));
  }
  if (is_face) {
    first_.reserve(e.count + 1);
    corners_.reserve(3 * e.count);
    for (ScalarOut& o : face_out_) o.values.reserve(e.count * static_cast<std::size_t>(o.dim));
  }
  std::vector<double> uv_record;
  const std::uint64_t fast =
      header_.format != Format::kAscii ? read_binary_records(e, is_vertex, is_face) : 0;
  for (std::uint64_t r = fast; r < e.count; ++r) {
    begin_record(e, r);
    std::size_t corners_before = corners_.size();
    bool saw_uv = false;
    uv_record.clear();
    for (const Property& p : e.props) {
      if (p.is_list) {
        Value count = read_value(p.count_type, e, r, p.name);
        if (count.i < 0)
          fail(where_now(), element_ref(e, r) + ": negative list count " + std::to_string(count.i) +
                                " for '" + p.name + "'");
        if (header_.format != Format::kAscii &&
            static_cast<std::uint64_t>(count.i) * type_size(p.type) > data_.size() - pos_)
          fail("byte " + std::to_string(pos_), element_ref(e, r) + ": list '" + p.name + "' of " +
                                                   std::to_string(count.i) +
                                                   " items runs past the end of the file");
        if (p.target == Target::kIndices && count.i < 3)
          fail(where_now(), "face " + std::to_string(r) + ": " + std::to_string(count.i) +
                                " corners (at least 3 needed)");
        for (std::int64_t k = 0; k < count.i; ++k) {
          Value item = read_value(p.type, e, r, p.name);
          if (p.target == Target::kIndices) {
            if (item.i < 0 || static_cast<std::uint64_t>(item.i) >= vertex_count_)
              fail(where_now(), "face " + std::to_string(r) + ": vertex index " +
                                    std::to_string(item.i) + " out of range (" +
                                    std::to_string(vertex_count_) + " vertices)");
            corners_.push_back(static_cast<std::uint32_t>(item.i));
          } else if (p.target == Target::kCornerUV) {
            if (!std::isfinite(item.d))
              fail(where_now(), "face " + std::to_string(r) + ": non-finite texcoord value");
            uv_record.push_back(item.d);
          }
        }
        if (p.target == Target::kCornerUV) saw_uv = true;
        continue;
      }
      Value v = read_value(p.type, e, r, p.name);
      if (p.target == Target::kSkip) continue;
      if (!std::isfinite(v.d))
        fail(where_now(), element_ref(e, r) + ": property '" + p.name + "' is not finite (" +
                              std::to_string(v.d) + ")");
      const std::size_t i = static_cast<std::size_t>(r);
      if (is_vertex) {
        store_vertex_value(p, i, v.d);
      } else if (is_face) {
        ScalarOut& o = face_out_[p.target == Target::kColor   ? face_color_out_
                                 : p.target == Target::kAlpha ? face_alpha_out_
                                                              : p.index];
        if (p.target == Target::kColor) {
          o.values.resize(3 * (i + 1));
          o.values[3 * i + p.index] = v.d / o.scale;
        } else {
          o.values.push_back(v.d / o.scale);
        }
      }
    }
    end_record(e, r);
    if (is_face) {
      const std::size_t n = corners_.size() - corners_before;
      if (has_corner_uv_) {
        if (!saw_uv || uv_record.size() != 2 * n)
          fail(where_now(), "face " + std::to_string(r) + ": texcoord list has " +
                                std::to_string(uv_record.size()) + " values, expected " +
                                std::to_string(2 * n) + " (2 per corner)");
        corner_uv_.insert(corner_uv_.end(), uv_record.begin(), uv_record.end());
      }
      first_.push_back(corners_.size());
    }
  }
}

void PlyParser::read_body() {
  if (header_.format == Format::kAscii) {
    lines_ = LineReader(data_, header_.body, header_.body_line - 1);
  } else {
    pos_ = header_.body;
  }
  for (Element& e : header_.elements) read_element(e);
  if (header_.format == Format::kAscii) {
    std::string_view line;
    while (lines_.next(line))
      if (!io_detail::trim(line).empty())
        fail(line_at(lines_.line_number()), "extra data after the last declared element (" +
                                                quoted(io_detail::trim(line)) +
                                                "); header counts smaller than the data?");
  } else if (pos_ != data_.size()) {
    fail("byte " + std::to_string(pos_),
         std::to_string(data_.size() - pos_) +
             " bytes of extra data after the last declared element");
  }
}

TriMesh PlyParser::parse() {
  const std::uint16_t probe = 1;
  unsigned char first_byte;
  std::memcpy(&first_byte, &probe, 1);
  little_host_ = first_byte == 1;

  parse_header();
  swap_ = header_.format != Format::kAscii && (header_.format == Format::kBinaryLE) != little_host_;
  for (Element& e : header_.elements) {
    if (e.name == "vertex") {
      if (e.count > std::numeric_limits<std::uint32_t>::max() - 1ull)
        fail(line_at(e.line), "vertex count " + std::to_string(e.count) + " is too large");
      vertex_count_ = e.count;
      have_vertex_ = true;
      plan_vertex(e);
    }
  }
  if (!have_vertex_) fail("", "no 'vertex' element in the header");
  for (Element& e : header_.elements)
    if (e.name == "face") {
      face_element_ = &e;
      plan_face(e);
    }
  read_body();
  if (vertex_count_ == 0) fail("", "no vertices (element vertex 0)");

  TriMesh mesh;
  mesh.source_file = path_;
  mesh.positions = std::move(positions_);
  if (faces_are_triangles_) {  // (no face or corner values: read_triangle_records' layout)
    assert(face_out_.empty() && !has_corner_uv_ && first_.size() == 1);
    mesh.faces = std::move(triangles_);
    mesh.source_polygons = mesh.faces.size();
  }
  const std::size_t polygons = first_.size() - 1;
  if (!faces_are_triangles_) mesh.source_polygons = polygons;
  mesh.faces.reserve(mesh.faces.size() + corners_.size() - 2 * polygons);
  for (std::size_t p = 0; p < polygons; ++p)
    for (std::size_t c = first_[p] + 1; c + 1 < first_[p + 1]; ++c)
      mesh.faces.push_back({corners_[first_[p]], corners_[c], corners_[c + 1]});

  for (ScalarOut& o : vertex_out_) {
    AttributeChannel& ch = mesh.add_channel(o.name, o.kind, Storage::kPerVertex, o.dim);
    ch.values = std::move(o.values);
  }
  // Per-face and per-corner values follow the fan triangulation.
  if (has_corner_uv_) {
    AttributeChannel& ch =
        mesh.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerCorner, 2);
    std::size_t f = 0;
    for (std::size_t p = 0; p < polygons; ++p) {
      const std::size_t c0 = first_[p];
      for (std::size_t c = c0 + 1; c + 1 < first_[p + 1]; ++c, ++f) {
        const std::size_t corner[3] = {c0, c, c + 1};
        for (std::size_t i = 0; i < 3; ++i)
          for (std::size_t k = 0; k < 2; ++k)
            ch.values[(3 * f + i) * 2 + k] = corner_uv_[corner[i] * 2 + k];
      }
    }
  }
  for (ScalarOut& o : face_out_) {
    AttributeChannel& ch = mesh.add_channel(o.name, o.kind, Storage::kPerFace, o.dim);
    const std::size_t d = static_cast<std::size_t>(o.dim);
    std::size_t f = 0;
    for (std::size_t p = 0; p < polygons; ++p)
      for (std::size_t c = first_[p] + 1; c + 1 < first_[p + 1]; ++c, ++f)
        for (std::size_t k = 0; k < d; ++k) ch.values[f * d + k] = o.values[p * d + k];
  }
  if (!header_.texture_file.empty())
    mesh.texture_file =
        io_detail::resolve_relative(io_detail::folder_of(path_), header_.texture_file);
  return mesh;
}

}  // namespace

TriMesh read_ply(const std::string& path, std::string_view content) {
  return PlyParser(path, content).parse();
}

}  // namespace meshdev
