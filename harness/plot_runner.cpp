// fork + execv of /usr/bin/python3 plot_curves.py, stdout captured through a pipe.
#include "harness/plot_runner.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "metric/errors.h"

#ifndef MESHDEV_PLOT_SCRIPT
#define MESHDEV_PLOT_SCRIPT ""
#endif

namespace meshdev::harness {
namespace {

std::string find_script() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("MESHDEV_PLOT_SCRIPT"); env && *env) return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share/meshdev/plot_curves.py";
    if (fs::exists(installed)) return installed.string();
  }
  if (fs::exists(MESHDEV_PLOT_SCRIPT)) return MESHDEV_PLOT_SCRIPT;
  throw InvalidInput(
      "plot_curves.py not found (set MESHDEV_PLOT_SCRIPT to harness/plot/plot_curves.py)");
}

}  // namespace

PlotResult run_plot_script(const std::string& csv, const PlotOptions& options) {
  PlotResult result;
  result.script = find_script();
  const char* py = std::getenv("MESHDEV_PYTHON");
  result.python = py && *py ? py : "/usr/bin/python3";
  if (::access(result.python.c_str(), X_OK) != 0)
    throw InvalidInput(result.python + " not found (apt-get install python3 python3-matplotlib)");
  std::vector<std::string> args = {result.python, result.script, csv, "--out", options.out_dir};
  args.insert(args.end(), options.extra_args.begin(), options.extra_args.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  int pipe_fd[2];
  if (::pipe(pipe_fd) != 0) throw IoError(std::string("pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) throw IoError(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    ::dup2(pipe_fd[1], 1);
    ::close(pipe_fd[0]);
    ::close(pipe_fd[1]);
    ::execv(argv[0], argv.data());
    _exit(127);
  }
  ::close(pipe_fd[1]);
  std::string out;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(pipe_fd[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    out.append(buf, static_cast<std::size_t>(n));
  }
  ::close(pipe_fd[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) result.files.push_back(line);
  return result;
}

}  // namespace meshdev::harness
