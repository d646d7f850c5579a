// The tidy results CSV: fixed header, RFC 4180 fields, round-trip numbers, torn-line tolerant.
#include "harness/results_csv.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "metric/errors.h"

namespace meshdev::harness {
namespace {

const char* const kStatNames[] = {
    "forward_mean",  "forward_rms",   "forward_max",  "forward_p95",    "backward_mean",
    "backward_rms",  "backward_max",  "backward_p95", "symmetric_mean", "symmetric_rms",
    "symmetric_max", "symmetric_p95", "hausdorff"};

std::vector<std::string> make_columns() {
  std::vector<std::string> c = {
      "job_key",          "mesh",           "mesh_hash",    "input_vertices",
      "input_faces",      "simplifier",     "options",      "reduction_percent",
      "status",           "message",        "target_faces", "reached_faces",
      "simplify_seconds", "metric_seconds", "measure",      "unit",
      "measure_index",    "measure_count",  "diagonal",     "samples_forward",
      "samples_backward", "sampling",       "seed",         "tool_version"};
  for (const char* s : kStatNames) c.emplace_back(s);
  for (const char* s : kStatNames) c.push_back(std::string(s) + "_rel");
  return c;
}

std::size_t column_index(const std::string& name) {
  const auto& cols = results_columns();
  const auto it = std::find(cols.begin(), cols.end(), name);
  if (it == cols.end()) throw std::logic_error("unknown results column '" + name + "'");
  return static_cast<std::size_t>(it - cols.begin());
}

std::string quote_field(const std::string& f) {
  if (f.find_first_of(",\"\r\n") == std::string::npos) return f;
  std::string out = "\"";
  for (char ch : f) {
    if (ch == '"') out += '"';
    // A line break inside a field would break the one-record-per-line rule of the reader.
    out += (ch == '\n' || ch == '\r') ? ' ' : ch;
  }
  out += '"';
  return out;
}

}  // namespace

const std::vector<std::string>& results_columns() {
  static const std::vector<std::string> columns = make_columns();
  return columns;
}

bool is_timing_column(const std::string& name) {
  return name == "simplify_seconds" || name == "metric_seconds";
}

ResultRow::ResultRow() : fields(results_columns().size()) {}

const std::string& ResultRow::get(const std::string& column) const {
  return fields[column_index(column)];
}

void ResultRow::set(const std::string& column, const std::string& value) {
  fields[column_index(column)] = value;
}

void ResultRow::set_number(const std::string& column, double value) {
  set(column, format_number(value));
}

void ResultRow::set_count(const std::string& column, std::size_t value) {
  set(column, std::to_string(value));
}

double ResultRow::number(const std::string& column) const {
  const std::string& text = get(column);
  if (text.empty()) return std::nan("");
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nan("");
  return v;
}

std::string format_number(double value) {
  if (!std::isfinite(value)) return "";
  char buf[64];
  // %.17g is locale-dependent only in the decimal point; the C locale is in force in meshdev
  // (we never call setlocale), and we normalise a comma just in case.
  std::snprintf(buf, sizeof buf, "%.17g", value);
  std::string s(buf);
  std::replace(s.begin(), s.end(), ',', '.');
  return s;
}

std::string format_header() {
  std::string line;
  for (std::size_t i = 0; i < results_columns().size(); ++i) {
    if (i) line += ',';
    line += results_columns()[i];
  }
  return line + '\n';
}

std::string format_row(const ResultRow& row) {
  std::string line;
  for (std::size_t i = 0; i < row.fields.size(); ++i) {
    if (i) line += ',';
    line += quote_field(row.fields[i]);
  }
  return line + '\n';
}

bool parse_csv_record(const std::string& line, std::vector<std::string>& fields) {
  fields.clear();
  std::string cur;
  bool quoted = false, was_quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"') {
          cur += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else {
        cur += ch;
      }
    } else if (ch == '"' && cur.empty() && !was_quoted) {
      quoted = was_quoted = true;
    } else if (ch == ',') {
      fields.push_back(cur);
      cur.clear();
      was_quoted = false;
    } else if (ch == '\r' && i + 1 == line.size()) {
      // tolerate CRLF files
    } else {
      cur += ch;
    }
  }
  if (quoted) return false;
  fields.push_back(cur);
  return true;
}

ParsedResults parse_results(const std::string& text, const std::string& source) {
  ParsedResults out;
  if (text.empty()) return out;
  const std::string header = format_header();
  const std::size_t header_end = text.find('\n');
  const std::string first =
      text.substr(0, header_end == std::string::npos ? text.size() : header_end + 1);
  if (first != header) {
    if (header_end == std::string::npos && header.compare(0, first.size(), first) == 0) {
      out.dropped_lines = 1;  // a torn header: the file holds no row yet
      out.warnings.push_back(source + ": torn header line dropped");
      return out;
    }
    throw ParseError(
        source, "line 1",
        "not a meshdev results CSV (the header differs from this version's; see docs/harness.md)");
  }
  std::vector<std::string> fields;
  std::size_t pos = header_end + 1, line_no = 1;
  while (pos < text.size()) {
    ++line_no;
    const std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) {
      ++out.dropped_lines;
      out.warnings.push_back(source + ": line " + std::to_string(line_no) +
                             ": torn last line (no line end) dropped");
      break;
    }
    const std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    if (line.empty()) continue;
    if (!parse_csv_record(line, fields) || fields.size() != results_columns().size()) {
      ++out.dropped_lines;
      out.warnings.push_back(source + ": line " + std::to_string(line_no) + ": " +
                             std::to_string(fields.size()) + " fields instead of " +
                             std::to_string(results_columns().size()) + ", dropped");
      continue;
    }
    ResultRow row;
    row.fields = fields;
    out.rows.push_back(std::move(row));
  }
  return out;
}

ParsedResults read_results_file(const std::string& path, bool missing_ok) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (missing_ok) return {};
    throw IoError(path + ": cannot open for reading");
  }
  std::ostringstream buf;
  buf << in.rdbuf();
  if (in.bad()) throw IoError(path + ": read failed");
  return parse_results(buf.str(), path);
}

std::string row_identity(const ResultRow& row) {
  return row.get("mesh") + '\x1f' + row.get("simplifier") + '\x1f' + row.get("options") + '\x1f' +
         format_number(row.number("reduction_percent")) + '\x1f' + row.get("measure");
}

void sort_rows(std::vector<ResultRow>& rows) {
  auto key = [](const ResultRow& r) {
    return std::make_tuple(r.get("mesh"), r.get("simplifier"), r.get("options"),
                           r.number("reduction_percent"), r.number("measure_index"));
  };
  std::stable_sort(rows.begin(), rows.end(),
                   [&](const ResultRow& x, const ResultRow& y) { return key(x) < key(y); });
}

}  // namespace meshdev::harness

namespace meshdev::harness {

std::vector<ResultRow> keep_complete_jobs(const std::vector<ResultRow>& rows,
                                          std::vector<std::string>& warnings) {
  std::map<std::string, std::vector<std::size_t>> by_key;
  for (std::size_t i = 0; i < rows.size(); ++i) by_key[rows[i].get("job_key")].push_back(i);
  std::vector<char> keep(rows.size(), 0);
  for (const auto& [key, idx] : by_key) {
    const double count = rows[idx.front()].number("measure_count");
    if (!(count >= 1) || count > 1e6) {
      warnings.push_back("job " + key + ": bad measure_count, its rows dropped");
      continue;
    }
    const auto n = static_cast<std::size_t>(count);
    std::vector<std::size_t> first(n, rows.size());
    bool bad = false;
    for (std::size_t i : idx) {
      const double m = rows[i].number("measure_index");
      if (!(m >= 0) || m >= count || rows[i].number("measure_count") != count) {
        bad = true;
        break;
      }
      const auto k = static_cast<std::size_t>(m);
      if (first[k] == rows.size()) first[k] = i;  // a repeat of a row is ignored
    }
    if (!bad && std::find(first.begin(), first.end(), rows.size()) != first.end()) bad = true;
    if (bad) {
      warnings.push_back("job " + key + ": incomplete (" + std::to_string(idx.size()) + " of " +
                         std::to_string(n) + " rows), dropped and recomputed on resume");
      continue;
    }
    if (idx.size() > n) warnings.push_back("job " + key + ": repeated rows, kept once");
    for (std::size_t i : first) keep[i] = 1;
  }
  std::vector<ResultRow> out;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (keep[i]) out.push_back(rows[i]);
  return out;
}

bool same_except_timing(const ResultRow& a, const ResultRow& b) {
  const auto& cols = results_columns();
  for (std::size_t i = 0; i < cols.size(); ++i)
    if (!is_timing_column(cols[i]) && a.fields[i] != b.fields[i]) return false;
  return true;
}

}  // namespace meshdev::harness
