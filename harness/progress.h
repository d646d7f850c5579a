#pragma once
// Progress of a sweep: on a terminal one redrawn bar with the ETA; otherwise one plain log line
// per finished job (for CI logs and Slurm output files). Thread-safe.
#include <chrono>
#include <cstddef>
#include <mutex>
#include <ostream>
#include <string>

namespace meshdev::harness {

class Progress {
 public:
  // `total` jobs to run in this invocation; `tty` selects the bar. Writes to `out`.
  Progress(std::ostream& out, bool tty, std::size_t total);

  // One job finished: `label` names it ("bunny00.off cgal-gh 90%"), `detail` says how it went.
  void job_done(const std::string& label, const std::string& detail);

  // Ends the bar's line (no-op for plain logs).
  void finish();

  // "1:02:03" / "2:03" from seconds. O(1).
  static std::string format_duration(double seconds);

 private:
  std::ostream& out_;
  bool tty_;
  std::size_t total_, done_ = 0;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
};

}  // namespace meshdev::harness
