#pragma once
// Each subcommand lives in its own cmd_<name>.cpp and registers itself on the root app. Its
// callback stores the command's exit code; exceptions are mapped to exit codes in main().
namespace CLI {
class App;
}

namespace meshdev::app {

void add_info_command(CLI::App& root, int& exit_code);
void add_simplify_command(CLI::App& root, int& exit_code);
void add_compare_command(CLI::App& root, int& exit_code);
void add_sweep_command(CLI::App& root, int& exit_code);
void add_plot_command(CLI::App& root, int& exit_code);
void add_guard_command(CLI::App& root, int& exit_code);
void add_merge_command(CLI::App& root, int& exit_code);
void add_render_command(CLI::App& root, int& exit_code);

}  // namespace meshdev::app
