#pragma once
// The error policy (docs/robustness.md, "Error policy"): bad input at a public entry point
// throws one of these typed exceptions; internal invariants use assert; run-time outcomes come
// back as values.
#include <stdexcept>
#include <string>

namespace meshdev {

// A precondition on the caller's data failed (empty mesh, attribute missing on one mesh, bad
// option value). The message says which mesh/option and what is wrong.
class InvalidInput : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A file could not be read or written (missing, unreadable, disk full, rename failed).
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output could not be written completely (disk full, folder missing, rename failed). Earlier
// results stay intact: outputs are written to a temporary name and renamed.
class WriteError : public IoError {
 public:
  using IoError::IoError;
};

// A mesh file is malformed. what() reads "<file>: <where>: <what is wrong>", where <where> is
// "line N", "byte N", "vertex N" or "face N".
class ParseError : public IoError {
 public:
  ParseError(const std::string& file, const std::string& where, const std::string& what)
      : IoError(file + ": " + (where.empty() ? std::string() : where + ": ") + what), file_(file) {}
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

}  // namespace meshdev
