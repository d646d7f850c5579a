// meshdev guard --baseline B.csv --current C.csv: exit 1 when a metric got worse.
#include <CLI/CLI.hpp>
#include <iostream>

#include "apps/commands.h"
#include "apps/exit_codes.h"
#include "harness/guard.h"
#include "harness/results_csv.h"
#include "harness/sweep_config.h"

namespace meshdev::app {
namespace {

struct GuardArgs {
  std::string baseline, current, tolerance = "5%", metrics, measures;
  double absolute_tolerance = 1e-12;
};

int run_guard_command(const GuardArgs& a) {
  harness::GuardOptions o;
  o.tolerance = harness::parse_tolerance(a.tolerance);
  o.absolute_tolerance = a.absolute_tolerance;
  if (!a.metrics.empty()) o.metrics = harness::split_list(a.metrics);
  if (!a.measures.empty()) o.measures = harness::split_list(a.measures);
  const harness::ParsedResults base = harness::read_results_file(a.baseline);
  const harness::ParsedResults cur = harness::read_results_file(a.current);
  for (const auto& w : base.warnings) std::cerr << "guard: warning: " << w << '\n';
  for (const auto& w : cur.warnings) std::cerr << "guard: warning: " << w << '\n';
  const harness::GuardResult r = harness::run_guard(base.rows, cur.rows, o);
  std::cout << harness::format_guard_report(r, o);
  return r.passed() ? kOk : kRegression;
}

}  // namespace

void add_guard_command(CLI::App& root, int& exit_code) {
  auto a = std::make_shared<GuardArgs>();
  auto* cmd = root.add_subcommand(
      "guard",
      "Regression guard: compare a sweep CSV with a baseline; exit 1 if anything got worse");
  cmd->footer(
      "Rows are paired by mesh, simplifier, options, ratio and measure. A regression is a\n"
      "metric above baseline x (1 + tolerance) + absolute tolerance, a baseline row missing\n"
      "from the current CSV, a failed status (failed, unavailable, metric-failed, input-error)\n"
      "or a changed status. Lower is better for every metric.\n"
      "Examples:\n"
      "  meshdev guard --baseline base/sweep.csv --current new/sweep.csv\n"
      "  meshdev guard --baseline b.csv --current c.csv --tolerance 2% "
      "--metrics symmetric_mean,hausdorff,symmetric_mean_rel --measures geometry,normal\n"
      "Exit codes: 0 nothing regressed, 1 regression (table on stdout), 2 usage, 3 unreadable "
      "CSV,\n4 bad metric name.");
  cmd->add_option("--baseline", a->baseline, "the reference results CSV")->required();
  cmd->add_option("--current", a->current, "the new results CSV")->required();
  cmd->add_option("--tolerance", a->tolerance, "allowed relative increase: 5% or 0.05")
      ->capture_default_str();
  cmd->add_option("--absolute-tolerance", a->absolute_tolerance,
                  "allowed absolute increase on top (covers baselines of 0)")
      ->capture_default_str();
  cmd->add_option("--metrics", a->metrics, "columns to check (default symmetric_mean,hausdorff)");
  cmd->add_option("--measures", a->measures, "measures to check (default: all)");
  cmd->callback([a, &exit_code] { exit_code = run_guard_command(*a); });
}

}  // namespace meshdev::app
