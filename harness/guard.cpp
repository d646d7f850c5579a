// Regression guard: baseline vs current results, tolerance per metric, failures and gaps count.
#include "harness/guard.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

#include "metric/errors.h"

namespace meshdev::harness {
namespace {

bool is_failure(const std::string& status) {
  return status != "ok" && status != "target-not-reached";
}

// Identity without the measure: the job a status row stands for.
std::string job_identity(const ResultRow& r) {
  return r.get("mesh") + '\x1f' + r.get("simplifier") + '\x1f' + r.get("options") + '\x1f' +
         format_number(r.number("reduction_percent"));
}

GuardFinding finding(const ResultRow& r, const std::string& metric, const std::string& verdict) {
  GuardFinding f;
  f.mesh = r.get("mesh");
  f.simplifier = r.get("simplifier") + (r.get("options").empty() ? "" : " " + r.get("options"));
  f.options = r.get("options");
  f.reduction_percent = r.get("reduction_percent");
  f.measure = r.get("measure");
  f.metric = metric;
  f.verdict = verdict;
  return f;
}

std::string short_number(const std::string& text) {
  if (text.empty()) return "-";
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return text;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

double parse_tolerance(const std::string& text) {
  const bool percent = !text.empty() && text.back() == '%';
  const std::string number = percent ? text.substr(0, text.size() - 1) : text;
  char* end = nullptr;
  const double v = std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size() || !(v >= 0) || !std::isfinite(v))
    throw InvalidInput("tolerance '" + text + "': give a percentage (5%) or a fraction (0.05)");
  return percent ? v / 100.0 : v;
}

GuardResult run_guard(const std::vector<ResultRow>& baseline, const std::vector<ResultRow>& current,
                      const GuardOptions& options) {
  const auto& cols = results_columns();
  static const std::vector<std::string> text_columns = {
      "job_key", "mesh",    "mesh_hash", "simplifier", "options",     "status",
      "message", "measure", "unit",      "sampling",   "tool_version"};
  for (const std::string& m : options.metrics)
    if (std::find(cols.begin(), cols.end(), m) == cols.end() ||
        std::find(text_columns.begin(), text_columns.end(), m) != text_columns.end())
      throw InvalidInput("--metrics: '" + m +
                         "' is not a numeric results column (e.g. "
                         "symmetric_mean, hausdorff, forward_max, symmetric_mean_rel)");
  // Bounds that compare nothing, or NaN, would let every run pass.
  if (!(options.tolerance >= 0) || !std::isfinite(options.tolerance) ||
      !(options.absolute_tolerance >= 0) || !std::isfinite(options.absolute_tolerance)) {
    std::ostringstream m;
    m << "the tolerances must be finite and >= 0 (relative " << options.tolerance << ", absolute "
      << options.absolute_tolerance << ")";
    throw InvalidInput(m.str());
  }
  if (baseline.empty())
    throw InvalidInput("the baseline holds no result rows: there is nothing to guard");
  for (const std::string& m : options.measures)
    if (std::none_of(baseline.begin(), baseline.end(),
                     [&](const ResultRow& r) { return r.get("measure") == m; }))
      throw InvalidInput("--measures: '" + m + "' is the measure of no baseline row");
  auto wanted = [&](const ResultRow& r) {
    return options.measures.empty() || r.get("measure").empty() ||
           std::find(options.measures.begin(), options.measures.end(), r.get("measure")) !=
               options.measures.end();
  };

  std::map<std::string, const ResultRow*> cur, cur_status;
  for (const ResultRow& r : current) {
    cur.emplace(row_identity(r), &r);
    if (is_failure(r.get("status"))) cur_status.emplace(job_identity(r), &r);
  }
  std::map<std::string, const ResultRow*> base;
  for (const ResultRow& r : baseline) base.emplace(row_identity(r), &r);

  GuardResult out;
  // Every failed row of the current run is a regression.
  for (const ResultRow& r : current) {
    if (!wanted(r)) continue;
    if (is_failure(r.get("status"))) {
      GuardFinding f = finding(r, "status", "failed");
      f.current = r.get("status") + (r.get("message").empty() ? "" : ": " + r.get("message"));
      const auto b = base.find(row_identity(r));
      f.baseline = b == base.end() ? "" : b->second->get("status");
      out.regressions.push_back(f);
    }
    if (!base.count(row_identity(r))) ++out.new_rows;
  }
  for (const ResultRow& b : baseline) {
    if (!wanted(b) || is_failure(b.get("status"))) continue;  // nothing to hold a failure to
    const auto it = cur.find(row_identity(b));
    if (it == cur.end()) {
      if (cur_status.count(job_identity(b))) continue;  // reported above as failed
      GuardFinding f = finding(b, "row", "missing");
      f.baseline = b.get("status");
      f.current = "(no row)";
      out.regressions.push_back(f);
      continue;
    }
    const ResultRow& c = *it->second;
    ++out.rows_compared;
    if (c.get("status") != b.get("status")) {
      if (!is_failure(c.get("status"))) {
        GuardFinding f = finding(b, "status", "status changed");
        f.baseline = b.get("status");
        f.current = c.get("status");
        out.regressions.push_back(f);
      }
      continue;
    }
    for (const std::string& m : options.metrics) {
      const double bv = b.number(m), cv = c.number(m);
      if (std::isnan(bv)) continue;  // not measured in the baseline (e.g. _rel of normals)
      ++out.values_compared;
      GuardFinding f = finding(b, m, "");
      f.baseline = b.get(m);
      f.current = c.get(m);
      if (std::isnan(cv)) {
        f.verdict = "no value";
        out.regressions.push_back(f);
      } else if (cv > bv * (1 + options.tolerance) + options.absolute_tolerance) {
        f.verdict = "worse";
        f.change = bv != 0 ? cv / bv - 1 : INFINITY;
        out.regressions.push_back(f);
      }
    }
  }
  return out;
}

std::string format_guard_report(const GuardResult& result, const GuardOptions& options) {
  std::ostringstream s;
  s << "meshdev guard: " << (result.passed() ? "PASS" : "FAIL") << ": " << result.regressions.size()
    << " regression" << (result.regressions.size() == 1 ? "" : "s") << "; "
    << result.values_compared << " values in " << result.rows_compared
    << " rows compared (tolerance " << options.tolerance * 100 << "% + "
    << options.absolute_tolerance << " absolute; metrics";
  for (const std::string& m : options.metrics) s << ' ' << m;
  s << ")";
  if (result.new_rows) s << "; " << result.new_rows << " rows only in the current run";
  s << '\n';
  if (result.regressions.empty()) return s.str();
  std::vector<std::vector<std::string>> table = {{"mesh", "simplifier", "ratio%", "measure",
                                                  "metric", "baseline", "current", "change",
                                                  "verdict"}};
  for (const GuardFinding& f : result.regressions) {
    std::string change = "";
    if (f.verdict == "worse") {
      char buf[32];
      if (std::isfinite(f.change))
        std::snprintf(buf, sizeof buf, "%+.1f%%", f.change * 100);
      else
        std::snprintf(buf, sizeof buf, "from 0");
      change = buf;
    }
    const bool numeric = f.verdict == "worse" || f.verdict == "no value";
    table.push_back({f.mesh, f.simplifier, f.reduction_percent, f.measure.empty() ? "-" : f.measure,
                     f.metric, numeric ? short_number(f.baseline) : f.baseline,
                     numeric ? short_number(f.current) : f.current, change, f.verdict});
  }
  std::vector<std::size_t> width(table[0].size(), 0);
  for (const auto& row : table)
    for (std::size_t i = 0; i < row.size(); ++i) width[i] = std::max(width[i], row[i].size());
  for (const auto& row : table) {
    std::string line;
    for (std::size_t i = 0; i < row.size(); ++i) {
      std::string cell = row[i];
      if (i + 1 < row.size()) cell.resize(width[i] + 2, ' ');
      line += cell;
    }
    s << line << '\n';
  }
  return s.str();
}

}  // namespace meshdev::harness
