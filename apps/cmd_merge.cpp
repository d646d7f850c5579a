// meshdev merge -o OUT.csv SHARD.csv...: join the CSVs of sweep shards.
#include <CLI/CLI.hpp>
#include <iostream>

#include "apps/commands.h"
#include "apps/exit_codes.h"
#include "harness/results_csv.h"
#include "harness/shard.h"
#include "metric/io/atomic_file.h"

namespace meshdev::app {
namespace {

struct MergeArgs {
  std::string output;
  std::vector<std::string> inputs;
};

int run_merge(const MergeArgs& a) {
  const harness::MergeResult m = harness::merge_results(a.inputs);
  for (const std::string& w : m.warnings) std::cerr << "merge: warning: " << w << '\n';
  write_file_atomically(a.output, [&](std::ostream& out) {
    out << harness::format_header();
    for (const harness::ResultRow& r : m.rows) out << harness::format_row(r);
  });
  std::cerr << "merge: " << m.jobs << " jobs (" << m.rows.size() << " rows) from " << m.inputs
            << " files -> " << a.output << '\n';
  return kOk;
}

}  // namespace

void add_merge_command(CLI::App& root, int& exit_code) {
  auto a = std::make_shared<MergeArgs>();
  auto* cmd = root.add_subcommand("merge", "Join the results CSVs of sweep shards (--shard I/N)");
  cmd->footer(
      "Keeps complete jobs only, each once (the same job in two files must agree except for\n"
      "timings), in canonical order: the merge of all N shards equals a single-machine run.\n"
      "Example:\n"
      "  meshdev merge -o results/all.csv shards/*/sweep.csv\n"
      "Exit codes: 0 ok, 2 usage, 3 unreadable input, 4 conflicting rows, 5 output not written.");
  cmd->add_option("--output,-o", a->output, "the merged CSV")->required();
  cmd->add_option("inputs", a->inputs, "shard CSVs")->required();
  cmd->callback([a, &exit_code] { exit_code = run_merge(*a); });
}

}  // namespace meshdev::app
