// Progress bar (terminal) or log lines (pipes, files); ETA = elapsed / done x remaining.
#include "harness/progress.h"

#include <cmath>
#include <cstdio>

namespace meshdev::harness {

Progress::Progress(std::ostream& out, bool tty, std::size_t total)
    : out_(out), tty_(tty), total_(total), start_(std::chrono::steady_clock::now()) {}

std::string Progress::format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long s = std::lround(seconds);
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

void Progress::job_done(const std::string& label, const std::string& detail) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++done_;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = elapsed / static_cast<double>(done_) * static_cast<double>(total_ - done_);
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = total_ ? static_cast<int>(kWidth * done_ / total_) : kWidth;
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    std::string tail = label + ": " + detail;
    if (tail.size() > 60) tail = tail.substr(0, 57) + "...";
    out_ << "\r\033[K[" << bar << "] " << done_ << '/' << total_ << "  " << format_duration(elapsed)
         << " elapsed, ETA " << format_duration(eta) << "  " << tail << std::flush;
  } else {
    out_ << "sweep: [" << done_ << '/' << total_ << "] " << label << ": " << detail << " (elapsed "
         << format_duration(elapsed) << ", ETA " << format_duration(eta) << ")\n"
         << std::flush;
  }
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (tty_ && done_ > 0) out_ << '\n' << std::flush;
}

}  // namespace meshdev::harness
