#pragma once
// The sweep's results table: a tidy CSV with one row per mesh x simplifier x ratio x measure
// (geometry, normal, normal_angle, colour, ...) and a fixed header, so files from different
// meshes, attribute sets, shards and tool versions can be appended, merged and compared.
// A simplifier that fails gives one status row with an empty measure. Format: RFC 4180 (fields
// quoted when they hold a comma, quote, CR or LF; quotes doubled), "\n" line ends, numbers with
// "%.17g" (round-trip exact, locale-independent), NaN/Inf never written as numbers (empty field).
#include <cstddef>
#include <string>
#include <vector>

namespace meshdev::harness {

// The columns, in order (docs/harness.md explains each one).
const std::vector<std::string>& results_columns();

// Columns that hold wall-clock times: they differ between identical runs and are ignored when
// runs are compared (resume, merge and shard tests, guard).
bool is_timing_column(const std::string& name);

// One row as named text fields (the CSV stores text; numbers are formatted by format_number).
struct ResultRow {
  std::vector<std::string> fields;  // one per results_columns() entry

  ResultRow();
  const std::string& get(const std::string& column) const;
  void set(const std::string& column, const std::string& value);
  void set_number(const std::string& column, double value);  // NaN/Inf -> empty
  void set_count(const std::string& column, std::size_t value);
  // The field as a number; NaN when empty or not a number.
  double number(const std::string& column) const;
};

// "%.17g" in the C locale; "" for NaN or Inf.
std::string format_number(double value);

// The header line, then one line per row (each ending in "\n").
std::string format_header();
std::string format_row(const ResultRow& row);

// Splits one CSV record (without its line end) into fields, RFC 4180. Returns false for an
// unterminated quoted field. O(length).
bool parse_csv_record(const std::string& line, std::vector<std::string>& fields);

struct ParsedResults {
  std::vector<ResultRow> rows;    // complete rows in file order
  std::size_t dropped_lines = 0;  // torn or malformed lines that were skipped
  std::vector<std::string> warnings;
};

// Reads a results CSV body. The header must equal format_header() (throws ParseError naming
// the file otherwise). A last line without its "\n" (a torn write) or a line with the wrong
// field count is dropped and counted. Records never span lines: the writer never puts a line
// break inside a field. `source` names the file in messages. O(size).
ParsedResults parse_results(const std::string& text, const std::string& source);

// Reads `path` (IoError if unreadable) and parses it; a missing file gives an empty result
// when `missing_ok`.
ParsedResults read_results_file(const std::string& path, bool missing_ok = false);

// The identity of a row independent of tool version, timings and file contents: mesh,
// simplifier, options, ratio, measure. Used by guard to pair baseline and current rows.
std::string row_identity(const ResultRow& row);

// Sorts rows canonically: mesh, simplifier, options, ratio (numeric), measure_index. Stable.
void sort_rows(std::vector<ResultRow>& rows);

}  // namespace meshdev::harness

namespace meshdev::harness {

// Keeps the rows of complete jobs only: a job (job_key) is complete when it has measure_count
// rows with measure_index 0..measure_count-1, each once. Rows of incomplete jobs (a write torn
// by a crash) are dropped with a warning; a repeated complete job is kept once. Order kept.
// O(rows log rows).
std::vector<ResultRow> keep_complete_jobs(const std::vector<ResultRow>& rows,
                                          std::vector<std::string>& warnings);

// True when two rows are equal in every column except the timing columns.
bool same_except_timing(const ResultRow& a, const ResultRow& b);

}  // namespace meshdev::harness
