#pragma once
// The regression guard: pairs the rows of a baseline and a current results CSV by identity
// (mesh, simplifier, options, ratio, measure; not by job key, which includes the tool version)
// and reports every metric that got worse beyond a tolerance, every baseline row missing from
// the current run, and every failed status. `meshdev guard` exits 1 when anything regressed.
#include <cstddef>
#include <string>
#include <vector>

#include "harness/results_csv.h"

namespace meshdev::harness {

struct GuardOptions {
  double tolerance = 0.05;            // relative: worse when current > baseline x (1 + tolerance)
  double absolute_tolerance = 1e-12;  // ... + this (in the column's units), so 0 -> 1e-15 passes
  std::vector<std::string> metrics = {"symmetric_mean", "hausdorff"};  // columns, lower = better
  std::vector<std::string> measures;  // rows to check: empty = every measure
};

struct GuardFinding {
  std::string mesh, simplifier, options, reduction_percent, measure;
  std::string metric;             // the column, or "row" / "status"
  std::string baseline, current;  // values as in the CSVs
  double change = 0;              // relative change (current / baseline - 1); 0 if not numeric
  std::string verdict;            // "worse", "missing", "failed", "status changed", "no value"
};

struct GuardResult {
  std::vector<GuardFinding> regressions;
  std::size_t rows_compared = 0, values_compared = 0;
  std::size_t new_rows = 0;  // current rows with no baseline (reported, not regressions)
  bool passed() const { return regressions.empty(); }
};

// Parses "5%" or "0.05" (>= 0). Throws InvalidInput otherwise. O(1).
double parse_tolerance(const std::string& text);

// Compares the two row sets (as read from CSV). Throws InvalidInput for a metric that is not
// a numeric results column, a measure of no baseline row, an empty baseline, and tolerances
// that are negative or not finite (each would let any run pass). O(rows log rows x metrics).
GuardResult run_guard(const std::vector<ResultRow>& baseline, const std::vector<ResultRow>& current,
                      const GuardOptions& options);

// A readable report: one summary line, then an aligned table of the regressions. O(findings).
std::string format_guard_report(const GuardResult& result, const GuardOptions& options);

}  // namespace meshdev::harness
