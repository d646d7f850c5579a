#include "metric/io/read_off.h"

#include <omp.h>

#include <algorithm>
#include <cstdint>
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

// What the vertex and face records of an OFF file (or of a chunk of its lines) give.
struct OffRecords {
  std::vector<Vec3> positions;
  std::vector<Triangle> faces;
  std::vector<double> normals, colors, alphas, uvs;
  std::uint64_t records = 0;  // content lines read
  int color_dim = -1;         // components of the first vertex colour read (3 or 4), -1: none
  bool float_colors = false;  // some colour value written with '.', 'e' or 'E'
};

class OffParser {
 public:
  OffParser(const std::string& path, std::string_view content) : path_(path), content_(content) {}
  // The whole file, line by line (the serial parse, and the chunked parse's oracle).
  TriMesh parse() {
    read_header();
    read_records(lines_, 0, nv_ + nf_, records_);
    std::string_view line;
    if (next_content_line(lines_, line))
      fail(lines_, "extra data after the last of the " + std::to_string(nf_) + " faces (" +
                       quoted(line) + "); header counts smaller than the data?");
    return finish(std::move(records_));
  }
  // The chunked parse on `threads` threads with about `chunks` chunks of lines (see read_off);
  // *used_chunks: whether the chunks' result is returned.
  TriMesh parse_in_chunks(int chunks, int threads, bool* used_chunks);

 private:
  // The header: keyword, counts and their sanity checks; lines_ is then at the first record.
  void read_header();
  // Reads content lines from `lines` as records first .. first + count - 1 (vertices below nv_,
  // then faces) into `out` until `count` records are read or the lines end. Throws ParseError
  // naming the line where parse() would (a chunk's line numbers count from its start).
  void read_records(LineReader& lines, std::uint64_t first, std::uint64_t count,
                    OffRecords& out) const;
  void read_vertex(const LineReader& lines, std::string_view line, std::uint64_t v,
                   OffRecords& out) const;
  void read_face(const LineReader& lines, std::string_view line, std::uint64_t f,
                 OffRecords& out) const;
  TriMesh finish(OffRecords r) const;
  [[noreturn]] void fail(const LineReader& lines, const std::string& what) const {
    throw ParseError(path_, "line " + std::to_string(lines.line_number()), what);
  }
  [[noreturn]] void fail(const std::string& what) const { fail(lines_, what); }
  // The next line that is not empty once its comment is removed; false at the end.
  static bool next_content_line(LineReader& lines, std::string_view& line) {
    while (lines.next(line)) {
      line = io_detail::trim(io_detail::strip_comment(line));
      if (!line.empty()) return true;
    }
    return false;
  }
  bool next_content_line(std::string_view& line) { return next_content_line(lines_, line); }
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
  double number(const LineReader& lines, std::string_view token, const Where& what) const {
    double value = 0;
    NumberStatus s = io_detail::parse_double(token, value);
    if (s != NumberStatus::kOk)
      fail(lines, what.str() + ": " + io_detail::describe_bad_number(token, s));
    return value;
  }
  std::int64_t integer(const LineReader& lines, std::string_view token, const Where& what) const {
    std::int64_t value = 0;
    NumberStatus s = io_detail::parse_int(token, value);
    if (s == NumberStatus::kNotNumber)
      fail(lines, what.str() + ": " + quoted(token) + " is not an integer");
    if (s != NumberStatus::kOk) fail(lines, what.str() + ": " + quoted(token) + " is out of range");
    return value;
  }

  const std::string& path_;
  std::string_view content_;
  LineReader lines_{""};
  OffKind kind_;
  std::uint64_t nv_ = 0, nf_ = 0;
  int fixed_ = 3;  // values of a vertex line before its colour
  OffRecords records_;
};

void OffParser::read_header() {
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
      counts[n++] = integer(lines_, tok, {"count"});
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
  kind_ = kind;
  nv_ = nv;
  nf_ = nf;
  fixed_ = 3 + (kind.normal ? 3 : 0) + (kind.texcoord ? 2 : 0);
  records_.positions.reserve(nv);
  records_.faces.reserve(nf);
}

void OffParser::read_records(LineReader& lines, std::uint64_t first, std::uint64_t count,
                             OffRecords& out) const {
  std::string_view line;
  for (std::uint64_t r = first; r < first + count; ++r) {
    if (!next_content_line(lines, line)) {
      if (r < nv_)
        fail(lines,
             "file ends after " + std::to_string(r) + " of " + std::to_string(nv_) + " vertices");
      fail(lines,
           "file ends after " + std::to_string(r - nv_) + " of " + std::to_string(nf_) + " faces");
    }
    ++out.records;
    if (r < nv_)
      read_vertex(lines, line, r, out);
    else
      read_face(lines, line, r - nv_, out);
  }
}

void OffParser::read_vertex(const LineReader& lines, std::string_view line, std::uint64_t v,
                            OffRecords& out) const {
  std::string_view tok[16];
  int n = 0;
  Tokens vt(line);
  while (n < 16 && vt.next(tok[n])) ++n;
  const Where where{"vertex", v};
  const int fixed = fixed_;
  int cdim = n - fixed;
  if (kind_.color) {
    if (cdim != 3 && cdim != 4)
      fail(lines, where.str() + ": expected " + std::to_string(fixed + 3) + " or " +
                      std::to_string(fixed + 4) + " values (with RGB[A] colour), found " +
                      std::to_string(n));
    if (out.color_dim < 0) out.color_dim = cdim;
    if (cdim != out.color_dim)
      fail(lines, where.str() + ": colour has " + std::to_string(cdim) +
                      " components, earlier vertices " + std::to_string(out.color_dim));
  } else if (n != fixed) {
    fail(lines, where.str() + ": expected " + std::to_string(fixed) + " values, found " +
                    std::to_string(n));
  }
  int i = 0;
  Vec3 p;
  for (int k = 0; k < 3; ++k) p[k] = number(lines, tok[i++], where);
  out.positions.push_back(p);
  if (kind_.normal)
    for (int k = 0; k < 3; ++k) out.normals.push_back(number(lines, tok[i++], where));
  if (kind_.color) {
    for (int k = 0; k < cdim; ++k, ++i) {
      std::string_view c = tok[i];
      out.float_colors = out.float_colors || c.find_first_of(".eE") != std::string_view::npos;
      double value = number(lines, c, where);
      if (value < 0) fail(lines, where.str() + ": negative colour value " + quoted(c));
      (k < 3 ? out.colors : out.alphas).push_back(value);
    }
  }
  if (kind_.texcoord)
    for (int k = 0; k < 2; ++k) out.uvs.push_back(number(lines, tok[i++], where));
}

void OffParser::read_face(const LineReader& lines, std::string_view line, std::uint64_t f,
                          OffRecords& out) const {
  const Where where{"face", f};
  Tokens ft(line);
  std::string_view tok;
  ft.next(tok);
  std::int64_t n = integer(lines, tok, {"face", f, " corner count"});
  if (n < 3) fail(lines, where.str() + ": " + std::to_string(n) + " corners (at least 3 needed)");
  std::uint32_t first = 0, previous = 0;
  for (std::int64_t k = 0; k < n; ++k) {
    if (!ft.next(tok))
      fail(lines, where.str() + ": declares " + std::to_string(n) + " corners but the line has " +
                      std::to_string(k) + " indices");
    std::int64_t idx = integer(lines, tok, {"face", f, " index"});
    if (idx < 0 || static_cast<std::uint64_t>(idx) >= nv_)
      fail(lines, where.str() + ": vertex index " + std::to_string(idx) + " out of range (" +
                      std::to_string(nv_) + " vertices)");
    const auto corner = static_cast<std::uint32_t>(idx);
    // Fanned from the first corner as the corners are read; a face that fails leaves its
    // triangles behind, but a failure ends the parse.
    if (k == 0) first = corner;
    if (k >= 2) out.faces.push_back({first, previous, corner});
    previous = corner;
  }
  // What may follow: nothing, a colour-map index, or an RGB[A] colour (ignored, but checked).
  int extra = 0;
  while (ft.next(tok)) {
    ++extra;
    number(lines, tok, {"face", f, " colour"});
  }
  if (extra == 2 || extra > 4)
    fail(lines, where.str() + ": " + std::to_string(extra) + " values after the " +
                    std::to_string(n) +
                    " indices (expected none, a colour index or an RGB[A] colour)");
}

TriMesh OffParser::finish(OffRecords r) const {
  TriMesh mesh;
  mesh.source_file = path_;
  mesh.positions = std::move(r.positions);
  mesh.faces = std::move(r.faces);
  mesh.source_polygons = nf_;
  if (kind_.normal) {
    mesh.add_channel("normal", AttributeKind::kNormal, Storage::kPerVertex, 3).values =
        std::move(r.normals);
  }
  if (kind_.color) {
    const double scale = r.float_colors ? 1.0 : 255.0;
    for (double& c : r.colors) c /= scale;
    for (double& a : r.alphas) a /= scale;
    if (!r.float_colors)
      for (double c : r.colors)
        if (c > 1.0) fail("integer colour value above 255");
    mesh.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3).values =
        std::move(r.colors);
    if (r.color_dim == 4)
      mesh.add_channel("alpha", AttributeKind::kScalar, Storage::kPerVertex, 1).values =
          std::move(r.alphas);
  }
  if (kind_.texcoord)
    mesh.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerVertex, 2).values =
        std::move(r.uvs);
  return mesh;
}

template <class T>
void append(std::vector<T>& to, const std::vector<T>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

TriMesh OffParser::parse_in_chunks(int chunks, int threads, bool* used_chunks) {
  if (used_chunks != nullptr) *used_chunks = false;
  read_header();
  // The records' text cut at line starts; pass 1 counts each chunk's content lines, so that pass
  // 2 knows which record each chunk starts with (vertex or face, and its number).
  const std::string_view text = io_detail::strip_bom(content_);
  const std::vector<std::size_t> start = io_detail::line_chunks(text, lines_.offset(), chunks);
  const auto n = static_cast<std::int64_t>(start.size() - 1);
  const int team = threads > 0 ? threads : omp_get_max_threads();
  std::vector<std::uint64_t> count(static_cast<std::size_t>(n), 0);
#pragma omp parallel for num_threads(team) schedule(dynamic, 1)
  for (std::int64_t k = 0; k < n; ++k) {
    LineReader lines(text.substr(0, start[k + 1]), start[k]);
    std::string_view line;
    std::uint64_t records = 0;
    while (next_content_line(lines, line)) ++records;
    count[static_cast<std::size_t>(k)] = records;
  }
  std::uint64_t total = 0;
  std::vector<std::uint64_t> first(static_cast<std::size_t>(n));
  for (std::int64_t k = 0; k < n; ++k) {
    first[static_cast<std::size_t>(k)] = total;
    total += count[static_cast<std::size_t>(k)];
  }
  // Too few or too many records: parse() names the line where the file ends or the extra data.
  if (total != nv_ + nf_) return OffParser(path_, content_).parse();
  std::vector<OffRecords> parts(static_cast<std::size_t>(n));
  bool failed = false;
#pragma omp parallel for num_threads(team) schedule(dynamic, 1) reduction(|| : failed)
  for (std::int64_t k = 0; k < n; ++k) {
    try {
      LineReader lines(text.substr(0, start[k + 1]), start[k]);
      const auto c = static_cast<std::size_t>(k);
      read_records(lines, first[c], count[c], parts[c]);
    } catch (...) {   // (no exception may leave the parallel region)
      failed = true;  // parse() below finds the first error and names its line
    }
  }
  // The colour rule spans chunks: every vertex colour has as many components as the first.
  for (const OffRecords& p : parts)
    if (p.color_dim >= 0 && records_.color_dim < 0)
      records_.color_dim = p.color_dim;
    else if (p.color_dim >= 0 && p.color_dim != records_.color_dim)
      failed = true;
  if (failed) return OffParser(path_, content_).parse();
  for (const OffRecords& p : parts) {
    append(records_.positions, p.positions);
    append(records_.faces, p.faces);
    append(records_.normals, p.normals);
    append(records_.colors, p.colors);
    append(records_.alphas, p.alphas);
    append(records_.uvs, p.uvs);
    records_.float_colors = records_.float_colors || p.float_colors;
  }
  parts.clear();
  TriMesh mesh;
  try {
    mesh = finish(std::move(records_));
  } catch (const ParseError&) {  // its message names the line parse() ends on
    return OffParser(path_, content_).parse();
  }
  if (used_chunks != nullptr) *used_chunks = true;
  return mesh;
}

}  // namespace

TriMesh read_off(const std::string& path, std::string_view content, int threads) {
  const int chunks = io_detail::chunks_for(content.size(), threads);
  if (chunks == 1) return OffParser(path, content).parse();
  return OffParser(path, content).parse_in_chunks(chunks, threads, nullptr);
}

namespace detail {

TriMesh read_off_in_chunks(const std::string& path, std::string_view content, int chunks,
                           int threads, bool* used_chunks) {
  return OffParser(path, content).parse_in_chunks(chunks, threads, used_chunks);
}

}  // namespace detail

}  // namespace meshdev
