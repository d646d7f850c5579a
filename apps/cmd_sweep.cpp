// meshdev sweep [CONFIG]: simplify meshes at rising reduction ratios with several backends,
// measure each result, write a tidy CSV (resumable), then draw the curves.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "apps/commands.h"
#include "apps/exit_codes.h"
#include "harness/plot_runner.h"
#include "harness/shard.h"
#include "harness/sweep.h"
#include "harness/sweep_config.h"
#include "metric/compare.h"
#include "metric/errors.h"

namespace meshdev::app {
namespace {

struct SweepArgs {
  std::string config;
  std::vector<std::string> meshes;
  std::string simplifiers, ratios, sampling, step, attributes, normals, out, shard;
  std::size_t sample_count = 0;
  std::uint64_t seed = 0;
  int jobs = 0, threads = -1;
  bool no_plots = false, quiet = false, progress_bar = false, no_progress_bar = false;
  std::vector<std::string> plot_args;
};

int run_sweep_command(SweepArgs& args, CLI::App& cmd) {
  using namespace harness;
  SweepConfig config;
  if (!args.config.empty()) {
    config = read_sweep_config(args.config);
  } else if (args.meshes.empty()) {
    throw CLI::ValidationError("sweep", "give a CONFIG file or at least one --mesh");
  }
  // Flags override the config.
  if (!args.meshes.empty()) {
    config.meshes = args.meshes;
    config.base_dir.clear();
  }
  if (!args.simplifiers.empty()) {
    config.simplifiers.clear();
    if (args.simplifiers != "all")
      for (const std::string& s : split_list(args.simplifiers))
        config.simplifiers.push_back(parse_simplifier_spec(s));
  }
  if (!args.ratios.empty()) config.reduction_percent = parse_ratio_list(args.ratios);
  if (!args.sampling.empty()) config.sampling = args.sampling;
  if (!args.step.empty()) {
    if (args.step.back() != '%') throw CLI::ValidationError("--step", "give a percentage: 0.5%");
    config.step_fraction = std::stod(args.step.substr(0, args.step.size() - 1)) / 100.0;
    if (!(config.step_fraction > 0)) throw CLI::ValidationError("--step", "must be positive");
  }
  if (cmd.count("--sample-count")) config.sample_count = args.sample_count;
  if (cmd.count("--seed")) config.seed = args.seed;
  if (!args.attributes.empty())
    config.attributes =
        args.attributes == "auto" ? std::vector<std::string>{} : split_list(args.attributes);
  if (!args.normals.empty()) config.normals = args.normals;
  if (args.jobs > 0) config.jobs = args.jobs;
  if (args.threads >= 0) config.threads = args.threads;
  if (args.no_plots) config.plots = false;
  compare_options(config);  // validate sampling / normals before any work

  SweepOptions options;
  if (!args.out.empty())
    options.output_dir = args.out;
  else if (!config.output.empty())
    options.output_dir = args.config.empty()
                             ? config.output
                             : (std::filesystem::path(config.base_dir) / config.output).string();
  else
    options.output_dir =
        "results/" + (args.config.empty() ? std::string("sweep")
                                          : std::filesystem::path(args.config).stem().string());
  if (!args.shard.empty()) options.shard = parse_shard(args.shard);
  options.log = args.quiet ? nullptr : &std::cerr;
  options.tty = !args.no_progress_bar && (args.progress_bar || ::isatty(2));

  const SweepSummary s = run_sweep(config, options);
  if (!args.quiet)
    std::cerr << "sweep: " << s.jobs_run << " jobs computed (" << s.jobs_failed << " failed), "
              << s.jobs_present << " already present, " << s.jobs_in_shard << " in this shard of "
              << s.jobs_total << "; " << s.seconds << " s\n";
  std::cout << s.csv_path << '\n' << s.json_path << '\n';

  if (config.plots && s.complete) {
    PlotOptions po;
    po.out_dir = (std::filesystem::path(options.output_dir) / "plots").string();
    po.extra_args = args.plot_args;
    try {
      const PlotResult p = run_plot_script(s.csv_path, po);
      for (const std::string& f : p.files) std::cout << f << '\n';
      if (p.exit_code != 0)
        std::cerr << "sweep: warning: plotting failed (exit " << p.exit_code
                  << "); the CSV is complete: run `meshdev plot " << s.csv_path << "` later\n";
    } catch (const InvalidInput& e) {
      std::cerr << "sweep: warning: no plots: " << e.what() << '\n';
    }
  }
  return kOk;
}

}  // namespace

void add_sweep_command(CLI::App& root, int& exit_code) {
  auto args = std::make_shared<SweepArgs>();
  auto* cmd = root.add_subcommand(
      "sweep", "Simplify meshes at rising reduction ratios with several backends and measure each");
  cmd->footer(
      "Config (JSON; only \"meshes\" is required, see docs/harness.md):\n"
      "  {\"meshes\": [\"bunny00.off\"], \"simplifiers\": [\"cgal-gh\", {\"name\": "
      "\"openmesh-hausdorff\", \"options\": {\"tolerance\": \"1%\"}}],\n"
      "   \"ratios\": [50, 75, 90, 95, 98, 99], \"sampling\": \"vertices,faces\", "
      "\"sample_count\": 200000, \"seed\": 1}\n"
      "Outputs in --out (default results/<config name>/): sweep.csv (one row per mesh x "
      "simplifier x ratio x measure),\n"
      "sweep.json (config, tool version, seed), plots/. Re-running computes only missing rows.\n"
      "Examples:\n"
      "  meshdev sweep sweep.json --jobs 2\n"
      "  meshdev sweep --mesh bunny00.off --simplifiers cgal-gh,openmesh-quadric --ratios 50,90\n"
      "  meshdev sweep sweep.json --shard 3/8 --out shards/3   # then meshdev merge\n"
      "Exit codes: 0 ok (failed simplifiers are status rows), 2 usage, 3 unreadable config or "
      "mesh,\n4 unusable config (unknown simplifier or option), 5 output not written or locked, "
      "70 internal.");
  cmd->add_option("config", args->config, "sweep config (JSON)");
  cmd->add_option("--mesh", args->meshes, "mesh to sweep (repeatable; replaces the config's)");
  cmd->add_option("--simplifiers", args->simplifiers,
                  "comma-separated backends, name[:key=value...], or 'all' (default: every "
                  "available backend)");
  cmd->add_option("--ratios", args->ratios, "reductions in percent (default 50,75,90,95,98,99)");
  cmd->add_option("--sampling", args->sampling,
                  "vertices,edges,faces,montecarlo (default "
                  "vertices,faces)");
  cmd->add_option("--step", args->step, "sampling step as % of the bbox diagonal");
  cmd->add_option("--sample-count", args->sample_count,
                  "face samples per direction (default 10 x the larger face count)");
  cmd->add_option("--seed", args->seed, "Monte Carlo seed (default 1)");
  cmd->add_option("--attributes", args->attributes, "auto or a list: geometry,normal,color,...");
  cmd->add_option("--normals", args->normals, "auto, file, uniform, area, angle");
  cmd->add_option("--jobs,-j", args->jobs,
                  "(mesh, simplifier) groups run at once (default 1; OpenMP runs inside each)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--threads", args->threads,
                  "OpenMP threads per comparison (0 = cores/jobs, at most 1024)")
      ->check(CLI::Range(0, meshdev::kMaxThreads));
  cmd->add_option("--out,-o", args->out, "output folder");
  cmd->add_option("--shard", args->shard, "run only shard I of N (I/N, 0-based), e.g. 0/4");
  cmd->add_flag("--no-plots", args->no_plots, "do not draw the curves at the end");
  cmd->add_option("--plot-arg", args->plot_args, "extra argument for the plot script (repeatable)")
      ->allow_extra_args(false);
  cmd->add_flag("--progress", args->progress_bar,
                "progress bar even when stderr is not a terminal");
  cmd->add_flag("--no-progress", args->no_progress_bar, "plain log lines even on a terminal");
  cmd->add_flag("--quiet,-q", args->quiet, "no progress or summary on stderr");
  cmd->callback([args, cmd, &exit_code] { exit_code = run_sweep_command(*args, *cmd); });
}

}  // namespace meshdev::app
