#include "metric/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <streambuf>
#include <vector>

#include "metric/errors.h"

namespace meshdev {
namespace {

// A streambuf over a file descriptor that remembers the first write error (errno).
class FdBuffer : public std::streambuf {
 public:
  explicit FdBuffer(int fd) : fd_(fd), buffer_(1 << 16) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    if (error_ != 0) return false;
    const char* p = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0) {
      ssize_t n = ::write(fd_, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
        return false;
      }
      if (n == 0) {
        error_ = EIO;
        return false;
      }
      p += n;
      left -= static_cast<std::size_t>(n);
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return true;
  }

  int fd_;
  std::vector<char> buffer_;
  int error_ = 0;
};

[[noreturn]] void fail(const std::string& path, const std::string& what, int err) {
  throw WriteError(path + ": " + what + " (" + std::strerror(err) + ")");
}

// Runs body into fd; returns normally only if every byte reached the file.
void write_all(int fd, const std::string& path, const std::function<void(std::ostream&)>& body) {
  FdBuffer buffer(fd);
  std::ostream out(&buffer);
  body(out);
  out.flush();
  if (buffer.error() != 0) fail(path, "cannot write", buffer.error());
  if (!out) fail(path, "cannot write", EIO);
}

}  // namespace

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& body) {
  // Follow a symlink so that the link stays and its target is replaced.
  std::string target = path;
  char resolved[4096];
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode) &&
      ::realpath(path.c_str(), resolved) != nullptr)
    target = resolved;

  if (::stat(target.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) fail(path, "cannot write", EISDIR);
    // A device or FIFO: no rename possible, write straight into it.
    int fd = ::open(target.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd < 0) fail(path, "cannot open for writing", errno);
    try {
      write_all(fd, path, body);
    } catch (...) {
      ::close(fd);
      throw;
    }
    if (::close(fd) != 0) fail(path, "cannot close", errno);
    return;
  }

  const std::string temp = target + ".tmp." + std::to_string(::getpid());
  int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) fail(path, "cannot create temporary file " + temp, errno);
  auto cleanup = [&] {
    if (fd >= 0) ::close(fd);
    fd = -1;
    ::unlink(temp.c_str());
  };
  try {
    write_all(fd, path, body);
    if (::fsync(fd) != 0) fail(path, "cannot fsync", errno);
    int rc = ::close(fd);
    fd = -1;
    if (rc != 0) fail(path, "cannot close", errno);
    if (::rename(temp.c_str(), target.c_str()) != 0) fail(path, "cannot rename " + temp, errno);
  } catch (...) {
    cleanup();
    throw;
  }
}

void check_output_path(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) fail(path, "cannot write", EISDIR);
  std::string folder = std::filesystem::path(path).parent_path().string();
  if (folder.empty()) folder = ".";
  if (::stat(folder.c_str(), &st) != 0) fail(path, "cannot write in folder " + folder, errno);
  if (!S_ISDIR(st.st_mode)) fail(path, "cannot write in folder " + folder, ENOTDIR);
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    fail(path, "cannot write in folder " + folder, errno);
}

void make_output_folder(const std::string& folder) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (!error && !std::filesystem::is_directory(folder, error) && !error)
    error = std::make_error_code(std::errc::not_a_directory);
  if (error) throw WriteError(folder + ": cannot create the folder (" + error.message() + ")");
}

}  // namespace meshdev
