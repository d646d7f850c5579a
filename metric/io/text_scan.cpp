#include "metric/io/text_scan.h"

#include <algorithm>

#include <fcntl.h>
#include <omp.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "metric/errors.h"

namespace meshdev::io_detail {

namespace {

[[noreturn]] void io_fail(const std::string& path, const char* what, int err) {
  throw IoError(path + ": " + what + ": " + std::strerror(err));
}

// An open descriptor, closed when it goes out of scope.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

// Opens `path` for reading and stats it; a directory is refused as open(2) would refuse writing.
struct stat open_for_reading(const std::string& path, Descriptor& d) {
  d.fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (d.fd < 0) io_fail(path, "cannot open", errno);
  struct stat st {};
  if (::fstat(d.fd, &st) != 0) io_fail(path, "cannot stat", errno);
  if (S_ISDIR(st.st_mode)) io_fail(path, "cannot open", EISDIR);
  return st;
}

// Everything left to read from d (the files that are not mapped: pipes, procfs, a failed
// mapping; and the .mtl files).
std::string read_all(const std::string& path, const Descriptor& d, const struct stat& st) {
  std::string data;
  if (S_ISREG(st.st_mode)) data.reserve(static_cast<std::size_t>(st.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(d.fd, buffer, sizeof buffer);
    if (n < 0) {
      if (errno == EINTR) continue;
      io_fail(path, "cannot read", errno);
    }
    if (n == 0) break;
    data.append(buffer, static_cast<std::size_t>(n));
  }
  return data;
}

}  // namespace

std::string read_file_bytes(const std::string& path) {
  Descriptor d;
  const struct stat st = open_for_reading(path, d);
  return read_all(path, d, st);
}

FileBytes::FileBytes(const std::string& path) {
  Descriptor d;
  const struct stat st = open_for_reading(path, d);
  if (S_ISREG(st.st_mode) && st.st_size > 0) {
    const auto size = static_cast<std::size_t>(st.st_size);
#ifdef MESHDEV_EXACT_FILE_BUFFER
    // Sanitizer builds: the bytes in a heap block of exactly the file's size, so a parser's read
    // one byte past the end is reported (in a mapping it would read the page's zero tail).
    exact_ = std::make_unique<char[]>(size);
    std::size_t have = 0;
    while (have < size) {
      const ssize_t n = ::read(d.fd, exact_.get() + have, size - have);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) io_fail(path, "cannot read", errno);
      if (n == 0) break;  // the file shrank since fstat
      have += static_cast<std::size_t>(n);
    }
    map_ = exact_.get();
    size_ = have;
    return;
#endif
    void* p = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, d.fd, 0);
    if (p != MAP_FAILED) {
      (void)::madvise(p, size, MADV_WILLNEED);  // read ahead (a hint: its failure costs nothing)
      map_ = static_cast<const char*>(p);
      size_ = size;
      return;
    }
  }
  copy_ = read_all(path, d, st);
}

FileBytes::~FileBytes() {
  if (map_ != nullptr && !exact_) ::munmap(const_cast<char*>(map_), size_);
}

std::string_view strip_bom(std::string_view text) {
  if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  return text;
}

std::string folder_of(const std::string& path) {
  return std::filesystem::path(path).parent_path().string();
}

std::string resolve_relative(const std::string& folder, std::string_view name) {
  std::string n(trim(name));
  for (char& c : n)
    if (c == '\\') c = '/';
  while (n.size() > 2 && n[0] == '.' && n[1] == '/') n.erase(0, 2);
  std::filesystem::path p(n);
  if (p.is_absolute() || folder.empty()) return p.lexically_normal().string();
  return (std::filesystem::path(folder) / p).lexically_normal().string();
}

std::vector<std::size_t> line_chunks(std::string_view text, std::size_t begin, int chunks) {
  std::vector<std::size_t> cuts{begin};
  const std::size_t bytes = text.size() - begin;
  for (int k = 1; k < chunks; ++k) {
    std::size_t at = std::max(cuts.back(), begin + bytes * static_cast<std::size_t>(k) /
                                                       static_cast<std::size_t>(chunks));
    if (at > 0 && at < text.size() && text[at - 1] != '\n') {
      const std::size_t newline = text.find('\n', at);
      at = newline == std::string_view::npos ? text.size() : newline + 1;
    }
    if (at > cuts.back() && at < text.size()) cuts.push_back(at);
  }
  cuts.push_back(text.size());
  return cuts;
}

int chunks_for(std::size_t bytes, int threads) {
  const int team = threads > 0 ? threads : omp_get_max_threads();
  if (team == 1 || bytes < 2 * kChunkBytes) return 1;
  return static_cast<int>(
      std::min<std::size_t>(4 * static_cast<std::size_t>(team), bytes / kChunkBytes));
}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  std::size_t end = text_.find('\n', pos_);
  if (end == std::string_view::npos) end = text_.size();
  line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = end + 1;
  ++line_;
  return true;
}

std::string_view Tokens::rest() const {
  return trim(s_.substr(pos_ < s_.size() ? pos_ : s_.size()));
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

std::string_view strip_comment(std::string_view line) {
  std::size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

NumberStatus parse_double(std::string_view token, double& out) {
  std::string_view t = token;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  if (t.empty() || t.front() == '+') return NumberStatus::kNotNumber;
  const char* end = t.data() + t.size();
  auto [ptr, ec] = std::from_chars(t.data(), end, out, std::chars_format::general);
  if (ptr != end) return NumberStatus::kNotNumber;
  if (ec == std::errc::result_out_of_range) {
    // Overflow is an error; underflow to a subnormal or zero is a legitimate value.
    std::string copy(t);
    errno = 0;
    double v = std::strtod(copy.c_str(), nullptr);
    if (!std::isfinite(v) || std::fabs(v) > 1.0) return NumberStatus::kNotFinite;
    out = v;
    return NumberStatus::kOk;
  }
  if (ec != std::errc()) return NumberStatus::kNotNumber;
  return std::isfinite(out) ? NumberStatus::kOk : NumberStatus::kNotFinite;
}

NumberStatus parse_int(std::string_view token, std::int64_t& out) {
  std::string_view t = token;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  if (t.empty() || t.front() == '+') return NumberStatus::kNotNumber;
  const char* end = t.data() + t.size();
  auto [ptr, ec] = std::from_chars(t.data(), end, out);
  if (ptr != end) return NumberStatus::kNotNumber;
  if (ec == std::errc::result_out_of_range) return NumberStatus::kNotFinite;
  if (ec != std::errc()) return NumberStatus::kNotNumber;
  return NumberStatus::kOk;
}

std::string describe_bad_number(std::string_view token, NumberStatus status) {
  if (status == NumberStatus::kNotFinite) return quoted(token) + " is not a finite number in range";
  return quoted(token) + " is not a number";
}

std::string quoted(std::string_view token) {
  std::string out = "'";
  std::size_t n = 0;
  for (char ch : token) {
    if (++n > 40) {
      out += "...";
      break;
    }
    auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7f) {
      out += ch;
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
    }
  }
  return out + "'";
}

}  // namespace meshdev::io_detail
