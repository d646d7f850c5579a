#pragma once
// Running harness/plot/plot_curves.py (matplotlib) on a results CSV with Debian's python3.
#include <string>
#include <vector>

namespace meshdev::harness {

struct PlotOptions {
  std::string out_dir;                  // where the PNG/SVG/PDF files go
  std::vector<std::string> extra_args;  // passed to the script (--log, --relative, ...)
};

struct PlotResult {
  int exit_code = 0;               // the script's (0 ok, 3 unreadable CSV, 4 nothing to plot)
  std::vector<std::string> files;  // what it wrote (its stdout lines)
  std::string script, python;      // what ran
};

// The script: $MESHDEV_PLOT_SCRIPT, else the source tree's copy, else
// <dir of this program>/../share/meshdev/plot_curves.py. The interpreter: $MESHDEV_PYTHON, else
// /usr/bin/python3. Throws InvalidInput when either is missing. Runs it without a shell
// (fork + execv), its stderr passing through. O(rows) in the script.
PlotResult run_plot_script(const std::string& csv, const PlotOptions& options);

}  // namespace meshdev::harness
