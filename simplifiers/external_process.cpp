#include "simplifiers/external_process.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "metric/errors.h"

extern char** environ;

namespace meshdev {
namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Orphans of the group are re-parented to us instead of init (which may not reap them in a
// container), so we can reap them and kill(-pgid, 0) ends up failing with ESRCH.
void become_subreaper() {
  static const bool done = [] {
    prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0);
    return true;
  }();
  (void)done;
}

// Appends to a buffer that keeps only the last `cap` bytes.
void append_capped(std::string& buffer, const char* data, std::size_t n, std::size_t cap) {
  buffer.append(data, n);
  if (buffer.size() > 2 * cap + 4096) buffer.erase(0, buffer.size() - cap);
}

void trim_capped(std::string& buffer, std::size_t cap) {
  if (buffer.size() > cap) buffer.erase(0, buffer.size() - cap);
}

bool is_executable_file(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

}  // namespace

std::string signal_name(int signal) {
  switch (signal) {
    case SIGHUP:
      return "SIGHUP";
    case SIGINT:
      return "SIGINT";
    case SIGQUIT:
      return "SIGQUIT";
    case SIGILL:
      return "SIGILL";
    case SIGTRAP:
      return "SIGTRAP";
    case SIGABRT:
      return "SIGABRT";
    case SIGBUS:
      return "SIGBUS";
    case SIGFPE:
      return "SIGFPE";
    case SIGKILL:
      return "SIGKILL";
    case SIGUSR1:
      return "SIGUSR1";
    case SIGSEGV:
      return "SIGSEGV";
    case SIGUSR2:
      return "SIGUSR2";
    case SIGPIPE:
      return "SIGPIPE";
    case SIGALRM:
      return "SIGALRM";
    case SIGTERM:
      return "SIGTERM";
    case SIGXCPU:
      return "SIGXCPU";
    case SIGXFSZ:
      return "SIGXFSZ";
    default:
      return "signal " + std::to_string(signal);
  }
}

std::string last_lines(const std::string& text, int n) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) lines.push_back(line);
  }
  std::string out;
  for (std::size_t i = lines.size() > std::size_t(n) ? lines.size() - n : 0; i < lines.size(); ++i)
    out += (out.empty() ? "" : " | ") + lines[i].substr(0, 300);
  return out;
}

std::string find_program(const std::string& name) {
  if (name.empty()) return {};
  if (name.find('/') != std::string::npos) return is_executable_file(name) ? name : std::string();
  const char* path = std::getenv("PATH");
  std::string dirs = path != nullptr ? path : "/usr/local/bin:/usr/bin:/bin";
  std::size_t begin = 0;
  while (begin <= dirs.size()) {
    std::size_t end = dirs.find(':', begin);
    if (end == std::string::npos) end = dirs.size();
    std::string dir = dirs.substr(begin, end - begin);
    std::string candidate = (dir.empty() ? std::string(".") : dir) + "/" + name;
    if (is_executable_file(candidate)) return candidate;
    begin = end + 1;
  }
  return {};
}

std::string ProcessResult::describe() const {
  std::ostringstream s;
  if (!started) {
    s << "could not start: " << error;
  } else if (timed_out) {
    s << "timed out after " << seconds << " s ("
      << (needed_kill ? "SIGTERM ignored, SIGKILL" : "SIGTERM") << " sent to its process group)";
  } else if (exited) {
    s << "exit code " << exit_code;
  } else {
    s << "killed by " << signal_name(signal);
  }
  return s.str();
}

ProcessResult run_process(const ProcessOptions& options) {
  ProcessResult r;
  const auto start = Clock::now();
  if (options.argv.empty()) {
    r.error = "empty command";
    return r;
  }
  const std::string program = find_program(options.argv[0]);
  if (program.empty()) {
    r.error = "'" + options.argv[0] + "' not found or not executable (PATH lookup)";
    return r;
  }
  become_subreaper();

  // Everything the child needs is prepared before fork (no allocation after it).
  std::vector<char*> args;
  for (const std::string& a : options.argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::vector<std::string> env_strings;
  for (char** e = environ; *e != nullptr; ++e) {
    std::string entry = *e;
    std::string key = entry.substr(0, entry.find('='));
    bool overridden = std::any_of(options.env.begin(), options.env.end(),
                                  [&](const auto& kv) { return kv.first == key; });
    if (!overridden) env_strings.push_back(entry);
  }
  for (const auto& [k, v] : options.env) env_strings.push_back(k + "=" + v);
  std::vector<char*> envp;
  for (const std::string& e : env_strings) envp.push_back(const_cast<char*>(e.c_str()));
  envp.push_back(nullptr);

  int out[2], err[2], status_pipe[2];
  if (pipe2(out, O_CLOEXEC) != 0 || pipe2(err, O_CLOEXEC) != 0 ||
      pipe2(status_pipe, O_CLOEXEC) != 0) {
    r.error = std::string("pipe: ") + std::strerror(errno);
    return r;
  }
  const pid_t pid = fork();
  if (pid < 0) {
    r.error = std::string("fork: ") + std::strerror(errno);
    for (int fd : {out[0], out[1], err[0], err[1], status_pipe[0], status_pipe[1]}) close(fd);
    return r;
  }
  if (pid == 0) {
    // Child: own process group, /dev/null as stdin, pipes as stdout/stderr, default signals.
    setpgid(0, 0);
    sigset_t all;
    sigemptyset(&all);
    sigprocmask(SIG_SETMASK, &all, nullptr);
    for (int s : {SIGPIPE, SIGTERM, SIGINT, SIGHUP, SIGQUIT, SIGCHLD}) signal(s, SIG_DFL);
    int devnull = open("/dev/null", O_RDONLY);
    if (devnull >= 0) dup2(devnull, 0);
    dup2(out[1], 1);
    dup2(err[1], 2);
    if (!options.working_dir.empty() && chdir(options.working_dir.c_str()) != 0) {
      int e = errno;
      ssize_t ignored = write(status_pipe[1], &e, sizeof e);
      (void)ignored;
      _exit(127);
    }
    execve(program.c_str(), args.data(), envp.data());
    int e = errno;
    ssize_t ignored = write(status_pipe[1], &e, sizeof e);
    (void)ignored;
    _exit(127);
  }

  // Parent.
  setpgid(pid, pid);  // also here: no race with a kill before the child ran setpgid
  close(out[1]);
  close(err[1]);
  close(status_pipe[1]);
  int exec_errno = 0;
  ssize_t got = 0;
  do {
    got = read(status_pipe[0], &exec_errno, sizeof exec_errno);
  } while (got < 0 && errno == EINTR);
  close(status_pipe[0]);
  if (got == sizeof exec_errno) {
    int status = 0;
    waitpid(pid, &status, 0);
    close(out[0]);
    close(err[0]);
    r.error = "'" + program + "': " + std::strerror(exec_errno);
    r.seconds = since(start);
    return r;
  }
  r.started = true;
  r.pgid = pid;

  int fds[2] = {out[0], err[0]};
  std::string* buffers[2] = {&r.stdout_tail, &r.stderr_tail};
  std::size_t* totals[2] = {&r.stdout_bytes, &r.stderr_bytes};
  for (int fd : fds) fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);

  bool reaped = false, term_sent = false, kill_sent = false;
  Clock::time_point kill_at{}, reaped_at{};
  const auto deadline = start + std::chrono::duration_cast<Clock::duration>(
                                    std::chrono::duration<double>(options.timeout_seconds));
  const auto grace = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(options.grace_seconds));
  char chunk[65536];
  for (;;) {
    // Reap whatever of the group has ended (orphans come to us: we are a subreaper).
    for (;;) {
      int status = 0;
      pid_t w = waitpid(-pid, &status, WNOHANG);
      if (w <= 0) break;
      if (w == pid) {
        reaped = true;
        reaped_at = Clock::now();
        if (WIFEXITED(status)) r.exited = true, r.exit_code = WEXITSTATUS(status);
        if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
      }
    }
    const bool group_alive = kill(-pid, 0) == 0;
    const bool pipes_open = fds[0] >= 0 || fds[1] >= 0;
    const auto now = Clock::now();
    if (reaped && !group_alive && (!pipes_open || now - reaped_at > std::chrono::seconds(1)))
      break;  // done (a pipe still open here is held by an escaped process: stop reading it)
    // The timeout, or members that outlived the program: SIGTERM, then SIGKILL after the grace.
    // Members still there 0.5 s after the program ended are leftovers (xvfb-run's Xvfb, for
    // one, is still shutting down when xvfb-run returns).
    const bool leftovers =
        reaped && group_alive && now - reaped_at > std::chrono::milliseconds(500);
    if (!term_sent && (now >= deadline || leftovers)) {
      if (!reaped)
        r.timed_out = true;
      else
        r.killed_leftovers = true;
      kill(-pid, SIGTERM);
      term_sent = true;
      kill_at = now + grace;
    }
    if (term_sent && !kill_sent && now >= kill_at && group_alive) {
      kill(-pid, SIGKILL);
      kill_sent = true;
      if (!reaped) r.needed_kill = true;
    }
    if (kill_sent && now >= kill_at + std::chrono::seconds(5)) break;  // unkillable: give up
    if (kill_sent && group_alive) kill(-pid, SIGKILL);                 // members forked in between

    // Read what is there (at most 20 ms of waiting, so reaping and deadlines stay timely).
    pollfd p[2];
    int np = 0;
    for (int i = 0; i < 2; ++i)
      if (fds[i] >= 0) p[np++] = {fds[i], POLLIN, 0};
    if (np == 0) {
      usleep(5000);
      continue;
    }
    if (poll(p, np, 20) < 0 && errno != EINTR) break;
    for (int k = 0; k < np; ++k) {
      if (p[k].revents == 0) continue;
      int i = p[k].fd == fds[0] ? 0 : 1;
      for (;;) {
        ssize_t n = read(fds[i], chunk, sizeof chunk);
        if (n > 0) {
          *totals[i] += std::size_t(n);
          append_capped(*buffers[i], chunk, std::size_t(n), options.capture_bytes);
          continue;
        }
        if (n == 0 || (errno != EAGAIN && errno != EINTR)) {
          close(fds[i]);
          fds[i] = -1;
        }
        break;
      }
    }
  }
  for (int fd : fds)
    if (fd >= 0) close(fd);
  trim_capped(r.stdout_tail, options.capture_bytes);
  trim_capped(r.stderr_tail, options.capture_bytes);
  r.seconds = since(start);
  return r;
}

TempDir::TempDir(const std::string& prefix) {
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern =
      std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/" + prefix + "XXXXXX";
  std::vector<char> buf(pattern.begin(), pattern.end());
  buf.push_back('\0');
  if (mkdtemp(buf.data()) == nullptr)
    throw IoError("cannot create a temporary folder " + pattern + ": " + std::strerror(errno));
  path_ = buf.data();
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace meshdev
