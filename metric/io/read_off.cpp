#include "metric/io/read_off.h"

#include <vector>

#include "metric/errors.h"
#include "metric/io/text_scan.h"

namespace meshdev {
namespace {

using io_detail::LineReader;
using io_detail::NumberStatus;
using io_detail::quoted;
using io_detail::Tokens;

struct OffKind {
  bool texcoord = false, color = false, normal = false;
};

// Recognises [ST][C][N]OFF; false for anything else (4OFF, nOFF, ...).
bool parse_keyword(std::string_view k, OffKind& kind) {
  if (k.size() >= 2 && k.substr(0, 2) == "ST") kind.texcoord = true, k.remove_prefix(2);
  if (!k.empty() && k.front() == 'C') kind.color = true, k.remove_prefix(1);
  if (!k.empty() && k.front() == 'N') kind.normal = true, k.remove_prefix(1);
  return k == "OFF";
}

class OffParser {
 public:
  OffParser(const std::string& path, std::string_view content) : path_(path), content_(content) {}
  TriMesh parse();

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw ParseError(path_, "line " + std::to_string(lines_.line_number()), what);
  }
  // The next line that is not empty once its comment is removed; false at the end.
  bool next_content_line(std::string_view& line) {
    while (lines_.next(line)) {
      line = io_detail::trim(io_detail::strip_comment(line));
      if (!line.empty()) return true;
    }
    return false;
  }
  // What a value belongs to in an error message ("vertex 12", "face 3 index"): made into a string
  // only when a message is, not once per record.
  struct Where {
    static constexpr std::uint64_t kNone = ~std::uint64_t{0};
    const char* element;
    std::uint64_t index = kNone;  // kNone: not a record's value (the header's counts)
    const char* detail = "";
    std::string str() const {
      return element + (index == kNone ? std::string() : " " + std::to_string(index)) + detail;
    }
  };
  double number(std::string_view token, const Where& what) const {
    double value = 0;
    NumberStatus s = io_detail::parse_double(token, value);
    if (s != NumberStatus::kOk) fail(what.str() + ": " + io_detail::describe_bad_number(token, s));
    return value;
  }
  std::int64_t integer(std::string_view token, const Where& what) const {
    std::int64_t value = 0;
    NumberStatus s = io_detail::parse_int(token, value);
    if (s == NumberStatus::kNotNumber)
      fail(what.str() + ": " + quoted(token) + " is not an integer");
    if (s != NumberStatus::kOk) fail(what.str() + ": " + quoted(token) + " is out of range");
    return value;
  }

  const std::string& path_;
  std::string_view content_;
  LineReader lines_{""};
};

TriMesh OffParser::parse() {
  lines_ = LineReader(io_detail::strip_bom(content_));
  std::string_view line;
  if (!next_content_line(line))
    throw ParseError(path_, "", "no OFF header (only comments or blank lines)");
  Tokens t(line);
  std::string_view key;
  t.next(key);
  OffKind kind;
  if (!parse_keyword(key, kind))
    fail("expected an OFF keyword (OFF, COFF, NOFF, CNOFF, STOFF), found " + quoted(key));
  std::string_view counts_line = t.rest();
  if (counts_line.substr(0, 6) == "BINARY")
    fail("binary OFF is not supported (convert it to ascii OFF or PLY)");
  if (counts_line.empty() && !next_content_line(counts_line))
    fail("file ends before the vertex/face counts");
  std::int64_t counts[3] = {0, 0, 0};
  {
    Tokens c(counts_line);
    std::string_view tok;
    int n = 0;
    while (c.next(tok)) {
      if (n == 3) fail("too many values on the counts line (expected 'V F E')");
      counts[n++] = integer(tok, {"count"});
    }
    if (n < 2) fail("counts line needs the vertex and face counts ('V F E')");
  }
  if (counts[0] < 0 || counts[1] < 0 || counts[2] < 0)
    fail("negative count (" + std::to_string(counts[0]) + " vertices, " +
         std::to_string(counts[1]) + " faces)");
  // Every vertex line takes at least 6 bytes ("0 0 0\n"), every face line 8 ("3 0 1 2\n").
  const std::uint64_t remaining = content_.size() - std::min(content_.size(), lines_.offset());
  const std::uint64_t nv = static_cast<std::uint64_t>(counts[0]),
                      nf = static_cast<std::uint64_t>(counts[1]);
  if (nv > (remaining + 1) / 6 || nf > (remaining + 1) / 8 || nv * 6 + nf * 8 > remaining + 2)
    fail("header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
         " faces but only " + std::to_string(remaining) + " bytes follow");
  if (nv == 0) fail("no vertices (vertex count 0)");
  if (nv > 0xFFFFFFFEull) fail("vertex count " + std::to_string(nv) + " is too large");

  TriMesh mesh;
  mesh.source_file = path_;
  mesh.positions.reserve(nv);
  std::vector<double> normals, colors, alphas, uvs;
  const int fixed = 3 + (kind.normal ? 3 : 0) + (kind.texcoord ? 2 : 0);
  int color_dim = -1;
  bool float_colors = false;
  for (std::uint64_t v = 0; v < nv; ++v) {
    if (!next_content_line(line))
      fail("file ends after " + std::to_string(v) + " of " + std::to_string(nv) + " vertices");
    std::string_view tok[16];
    int n = 0;
    Tokens vt(line);
    while (n < 16 && vt.next(tok[n])) ++n;
    const Where where{"vertex", v};
    int cdim = n - fixed;
    if (kind.color) {
      if (cdim != 3 && cdim != 4)
        fail(where.str() + ": expected " + std::to_string(fixed + 3) + " or " +
             std::to_string(fixed + 4) + " values (with RGB[A] colour), found " +
             std::to_string(n));
      if (color_dim < 0) color_dim = cdim;
      if (cdim != color_dim)
        fail(where.str() + ": colour has " + std::to_string(cdim) +
             " components, earlier vertices " + std::to_string(color_dim));
    } else if (n != fixed) {
      fail(where.str() + ": expected " + std::to_string(fixed) + " values, found " +
           std::to_string(n));
    }
    int i = 0;
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = number(tok[i++], where);
    mesh.positions.push_back(p);
    if (kind.normal)
      for (int k = 0; k < 3; ++k) normals.push_back(number(tok[i++], where));
    if (kind.color) {
      for (int k = 0; k < cdim; ++k, ++i) {
        std::string_view c = tok[i];
        float_colors = float_colors || c.find_first_of(".eE") != std::string_view::npos;
        double value = number(c, where);
        if (value < 0) fail(where.str() + ": negative colour value " + quoted(c));
        (k < 3 ? colors : alphas).push_back(value);
      }
    }
    if (kind.texcoord)
      for (int k = 0; k < 2; ++k) uvs.push_back(number(tok[i++], where));
  }

  std::vector<std::uint32_t> poly;
  mesh.faces.reserve(nf);
  for (std::uint64_t f = 0; f < nf; ++f) {
    if (!next_content_line(line))
      fail("file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const Where where{"face", f};
    Tokens ft(line);
    std::string_view tok;
    ft.next(tok);
    std::int64_t n = integer(tok, {"face", f, " corner count"});
    if (n < 3) fail(where.str() + ": " + std::to_string(n) + " corners (at least 3 needed)");
    poly.clear();
    for (std::int64_t k = 0; k < n; ++k) {
      if (!ft.next(tok))
        fail(where.str() + ": declares " + std::to_string(n) + " corners but the line has " +
             std::to_string(k) + " indices");
      std::int64_t idx = integer(tok, {"face", f, " index"});
      if (idx < 0 || static_cast<std::uint64_t>(idx) >= nv)
        fail(where.str() + ": vertex index " + std::to_string(idx) + " out of range (" +
             std::to_string(nv) + " vertices)");
      poly.push_back(static_cast<std::uint32_t>(idx));
    }
    // What may follow: nothing, a colour-map index, or an RGB[A] colour (ignored, but checked).
    int extra = 0;
    while (ft.next(tok)) {
      ++extra;
      number(tok, {"face", f, " colour"});
    }
    if (extra == 2 || extra > 4)
      fail(where.str() + ": " + std::to_string(extra) + " values after the " + std::to_string(n) +
           " indices (expected none, a colour index or an RGB[A] colour)");
    for (std::size_t c = 1; c + 1 < poly.size(); ++c)
      mesh.faces.push_back({poly[0], poly[c], poly[c + 1]});
  }
  mesh.source_polygons = nf;
  if (next_content_line(line))
    fail("extra data after the last of the " + std::to_string(nf) + " faces (" + quoted(line) +
         "); header counts smaller than the data?");

  if (kind.normal) {
    mesh.add_channel("normal", AttributeKind::kNormal, Storage::kPerVertex, 3).values =
        std::move(normals);
  }
  if (kind.color) {
    const double scale = float_colors ? 1.0 : 255.0;
    for (double& c : colors) c /= scale;
    for (double& a : alphas) a /= scale;
    if (!float_colors)
      for (double c : colors)
        if (c > 1.0) fail("integer colour value above 255");
    mesh.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3).values =
        std::move(colors);
    if (color_dim == 4)
      mesh.add_channel("alpha", AttributeKind::kScalar, Storage::kPerVertex, 1).values =
          std::move(alphas);
  }
  if (kind.texcoord)
    mesh.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerVertex, 2).values =
        std::move(uvs);
  return mesh;
}

}  // namespace

TriMesh read_off(const std::string& path, std::string_view content) {
  return OffParser(path, content).parse();
}

}  // namespace meshdev
