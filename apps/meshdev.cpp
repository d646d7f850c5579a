// meshdev: how far one mesh is from another, in geometry and in appearance.
#include <malloc.h>
#include <CLI/CLI.hpp>

#include <climits>
#include <iostream>
#include <new>

#include "apps/commands.h"
#include "apps/exit_codes.h"
#include "metric/errors.h"

int main(int argc, char** argv) {
  using namespace meshdev::app;
  // glibc: large blocks from the heap instead of their own mappings, and freed memory kept by
  // the process. A comparison's second direction then reuses the first one's samples and
  // deviation arrays (about 100 MB for 1M samples) instead of faulting fresh pages in one by one:
  // half of `meshdev compare`'s page faults (docs/performance-log.md).
  // A failure (mallopt returns 0) costs speed only.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
  CLI::App app{"meshdev " MESHDEV_VERSION
               ": mesh comparison with the attribute deviation metric (Roy, Foufou, Truchetet)"};
  app.set_version_flag("--version", MESHDEV_VERSION);
  app.require_subcommand(1);
  int exit_code = kOk;
  add_info_command(app, exit_code);
  add_simplify_command(app, exit_code);
  add_compare_command(app, exit_code);
  add_sweep_command(app, exit_code);
  add_plot_command(app, exit_code);
  add_guard_command(app, exit_code);
  add_merge_command(app, exit_code);
  add_render_command(app, exit_code);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kOk : kUsage;
  } catch (const meshdev::WriteError& e) {
    std::cerr << "meshdev: error: " << e.what() << '\n';
    return kWriteError;
  } catch (const meshdev::IoError& e) {
    std::cerr << "meshdev: error: " << e.what() << '\n';
    return kInputError;
  } catch (const meshdev::InvalidInput& e) {
    std::cerr << "meshdev: error: " << e.what() << '\n';
    return kInvalidInput;
  } catch (const std::bad_alloc&) {
    std::cerr << "meshdev: error: out of memory\n";
    return kInternal;
  } catch (const std::exception& e) {
    std::cerr << "meshdev: internal error: " << e.what() << '\n';
    return kInternal;
  }
  return exit_code;
}
