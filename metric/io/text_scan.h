#pragma once
// Shared low-level pieces of the mesh readers (not part of the public API): reading a whole file,
// splitting text into lines and tokens, and strict number parsing with std::from_chars.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#define MESHDEV_EXACT_FILE_BUFFER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MESHDEV_EXACT_FILE_BUFFER 1
#endif
#endif

namespace meshdev::io_detail {

// The whole file as bytes. Throws IoError("<path>: cannot open: <strerror>") if it cannot be
// read (missing, a directory, no permission). O(file size).
std::string read_file_bytes(const std::string& path);

// The whole file's bytes for parsing: a regular file is mapped read-only (the parsers read the
// page cache: no copy, and no fresh memory to fault in, which took a third of a large binary
// PLY's load); anything else (a pipe, /dev/stdin, an empty file, a failed mapping) is read into
// memory as read_file_bytes does. Same errors as read_file_bytes. The file must not shrink while
// it is mapped (the system would end the process on a read past its new end). O(file size).
class FileBytes {
 public:
  explicit FileBytes(const std::string& path);
  ~FileBytes();
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  std::string_view view() const { return map_ != nullptr ? std::string_view(map_, size_) : copy_; }

 private:
  const char* map_ = nullptr;  // the mapping (or exact_), or nullptr when the bytes are in copy_
  std::size_t size_ = 0;
  std::string copy_;
  std::unique_ptr<char[]> exact_;  // sanitizer builds: the file in a block of its exact size
};

// `text` without a leading UTF-8 byte order mark.
std::string_view strip_bom(std::string_view text);

// The folder of `path` ("" for a bare file name), for resolving mtllib / map_Kd / TextureFile.
std::string folder_of(const std::string& path);

// `name` as written in a file (Windows `.\x.jpg` accepted) resolved against `folder`.
std::string resolve_relative(const std::string& folder, std::string_view name);

// Splits text into lines on '\n'; a trailing '\r' (CRLF) is removed. O(1) per line plus its length.
class LineReader {
 public:
  // Starts at byte `start`; the first line returned is numbered lines_before + 1.
  explicit LineReader(std::string_view text, std::size_t start = 0, std::size_t lines_before = 0)
      : text_(text), pos_(start), line_(lines_before) {}
  // The next line; false at the end of the text.
  bool next(std::string_view& line);
  // 1-based number of the line last returned by next().
  std::size_t line_number() const { return line_; }
  // Byte offset of the first byte not yet returned.
  std::size_t offset() const { return pos_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

// Where to cut text[begin, text.size()) into about `chunks` parts of equal bytes for parsing in
// parallel, each cut moved on to the start of a line: the chunks' first offsets, ascending and
// distinct, then text.size() (so chunk k is [cuts[k], cuts[k + 1])); fewer chunks where the text
// has fewer lines. Precondition: begin <= text.size(), at a line start. O(chunks + longest line).
std::vector<std::size_t> line_chunks(std::string_view text, std::size_t begin, int chunks);

// The least bytes per chunk of the readers' chunked parses (OBJ, OFF).
constexpr std::size_t kChunkBytes = std::size_t{1} << 19;

// How many chunks a reader cuts `bytes` of text into on `threads` OpenMP threads (0: the
// default): 1 (the line-by-line parse) on one thread or below 2 kChunkBytes, else up to 4 per
// thread of at least kChunkBytes each.
int chunks_for(std::size_t bytes, int threads);

inline bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f' || c == '\n';
}

// Whitespace-separated tokens of one line.
class Tokens {
 public:
  explicit Tokens(std::string_view line) : s_(line) {}
  // The next token; false when none is left.
  bool next(std::string_view& token) {
    while (pos_ < s_.size() && is_space(s_[pos_])) ++pos_;
    if (pos_ >= s_.size()) return false;
    std::size_t begin = pos_;
    while (pos_ < s_.size() && !is_space(s_[pos_])) ++pos_;
    token = s_.substr(begin, pos_ - begin);
    return true;
  }
  // Everything after the current position, trimmed.
  std::string_view rest() const;
  bool empty_rest() const { return rest().empty(); }

 private:
  std::string_view s_;
  std::size_t pos_ = 0;
};

// `s` without leading and trailing whitespace.
std::string_view trim(std::string_view s);

// `line` up to (not including) the first '#'.
std::string_view strip_comment(std::string_view line);

enum class NumberStatus { kOk, kNotNumber, kNotFinite };

// Parses a whole token as a finite double (an optional leading '+' is accepted). nan, inf and
// values overflowing double are kNotFinite; subnormal underflow is accepted.
NumberStatus parse_double(std::string_view token, double& out);

// Parses a whole token as a decimal integer (optional leading '+').
NumberStatus parse_int(std::string_view token, std::int64_t& out);

// "'abc' is not a number" / "'nan' is not a finite number", for error messages.
std::string describe_bad_number(std::string_view token, NumberStatus status);

// `token` quoted for an error message: at most 40 characters, non-printable bytes as \xNN.
std::string quoted(std::string_view token);

}  // namespace meshdev::io_detail
