#pragma once
// Running an external program safely (docs/simplifiers.md "External processes";
// research/reliability.md §5D): its own process group, stdin from /dev/null, stdout and stderr
// captured through poll() with a cap (no deadlock on a flood), a timeout that sends SIGTERM to the
// whole group and SIGKILL after a grace period, and no process of the group left behind — even a
// child that outlives the program or ignores SIGTERM. POSIX (Linux) only.
#include <sys/types.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace meshdev {

struct ProcessOptions {
  std::vector<std::string> argv;  // program (a path, or a name looked up in PATH) and arguments
  std::string working_dir;        // "" = the caller's
  std::vector<std::pair<std::string, std::string>> env;  // set in the child, on top of ours
  double timeout_seconds = 300;                          // wall time before SIGTERM to the group
  double grace_seconds = 2;                              // between SIGTERM and SIGKILL
  std::size_t capture_bytes = 64 * 1024;  // keep the LAST this many bytes of stdout and of stderr
};

struct ProcessResult {
  bool started = false;  // false: the program could not be started (`error` says why)
  bool exited = false;   // exited normally with exit_code
  int exit_code = -1;
  int signal = 0;                        // the signal that ended it (0 if it exited)
  bool timed_out = false;                // the timeout fired (then signal is SIGTERM or SIGKILL)
  bool needed_kill = false;              // SIGTERM was not enough: SIGKILL was sent
  bool killed_leftovers = false;         // group members outlived the program and were terminated
  std::string stdout_tail, stderr_tail;  // the last capture_bytes of each
  std::size_t stdout_bytes = 0, stderr_bytes = 0;  // everything it wrote
  double seconds = 0;
  pid_t pgid = 0;     // its process group (== its pid); gone when run_process returns
  std::string error;  // why it did not start

  // "exit code 3", "killed by SIGSEGV", "timed out after 2 s (SIGTERM)", "could not start: ...".
  std::string describe() const;
  // Succeeded: started, exited with 0, no timeout.
  bool ok() const { return started && exited && exit_code == 0 && !timed_out; }
};

// Runs argv[0] with the options; returns when the program has ended and every process of its
// group is gone (at most timeout + grace + ~1 s). Never throws for the program's behaviour.
// Makes the calling process a child subreaper (prctl) so that orphans of the group are reaped.
ProcessResult run_process(const ProcessOptions& options);

// The full path of an executable `name` (searched in PATH unless it contains '/'), or "".
std::string find_program(const std::string& name);

// "SIGSEGV", "SIGKILL", ... or "signal N".
std::string signal_name(int signal);

// The last `n` non-empty lines of `text`, joined with " | ".
std::string last_lines(const std::string& text, int n);

// A fresh private folder (mkdtemp under $TMPDIR or /tmp) removed with its contents on
// destruction. Throws IoError when it cannot be created.
class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "meshdev-");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

}  // namespace meshdev
