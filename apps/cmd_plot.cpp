// meshdev plot CSV: Fig. 8-style curves (deviation vs reduction, one line per simplifier).
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "apps/commands.h"
#include "apps/exit_codes.h"
#include "harness/plot_runner.h"

namespace meshdev::app {
namespace {

struct PlotArgs {
  std::string csv, out, statistic = "symmetric_mean", measures, formats = "png,svg,pdf",
                        x = "ratio";
  bool log = false, relative = false;
};

int run_plot(const PlotArgs& a) {
  harness::PlotOptions o;
  o.out_dir =
      a.out.empty() ? (std::filesystem::path(a.csv).parent_path() / "plots").string() : a.out;
  o.extra_args = {"--statistic", a.statistic, "--formats", a.formats, "--x", a.x};
  if (!a.measures.empty()) o.extra_args.insert(o.extra_args.end(), {"--measures", a.measures});
  if (a.log) o.extra_args.push_back("--log");
  if (a.relative) o.extra_args.push_back("--relative");
  const harness::PlotResult r = harness::run_plot_script(a.csv, o);
  for (const std::string& f : r.files) std::cout << f << '\n';
  if (r.exit_code == 0) return kOk;
  if (r.exit_code == 3) return kInputError;
  if (r.exit_code == 4 || r.exit_code == 127) return kInvalidInput;
  if (r.exit_code == 5) return kWriteError;
  return r.exit_code == 2 ? kUsage : kInternal;
}

}  // namespace

void add_plot_command(CLI::App& root, int& exit_code) {
  auto a = std::make_shared<PlotArgs>();
  auto* cmd = root.add_subcommand(
      "plot", "Curves from a sweep CSV: mean symmetric deviation vs reduction, per simplifier");
  cmd->footer(
      "Draws with matplotlib (Debian python3-matplotlib, run by /usr/bin/python3).\n"
      "One figure per mesh and measure (<mesh>_<measure>.png/.svg/.pdf) and a two-panel\n"
      "<mesh>_fig8 figure: (a) geometric, (b) normal deviation, like the paper's Fig. 8.\n"
      "Examples:\n"
      "  meshdev plot results/demo/sweep.csv\n"
      "  meshdev plot sweep.csv --log --relative --out figs --formats pdf\n"
      "Exit codes: 0 ok, 2 usage, 3 unreadable CSV, 4 nothing to plot or no matplotlib.");
  cmd->add_option("csv", a->csv, "results CSV written by meshdev sweep or merge")->required();
  cmd->add_option("--out,-o", a->out, "output folder (default: plots/ beside the CSV)");
  cmd->add_option("--statistic", a->statistic,
                  "column to plot: symmetric_mean (paper Fig. 8), symmetric_rms, hausdorff, ...")
      ->capture_default_str();
  cmd->add_option("--measures", a->measures, "comma-separated (default: every measure)");
  cmd->add_option("--formats", a->formats,
                  "comma-separated: png,svg,pdf or any other format matplotlib writes (eps, jpg, "
                  "tif, ...)")
      ->capture_default_str();
  cmd->add_option("--x", a->x, "x axis: ratio (reduction %) or faces (reached, log)")
      ->check(CLI::IsMember({"ratio", "faces"}))
      ->capture_default_str();
  cmd->add_flag("--log", a->log, "logarithmic y axis");
  cmd->add_flag("--relative", a->relative, "geometry as a fraction of the bbox diagonal");
  cmd->callback([a, &exit_code] { exit_code = run_plot(*a); });
}

}  // namespace meshdev::app
