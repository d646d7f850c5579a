#pragma once
// Helpers of the reader/writer tests: tiny files written from strings or bytes, and a check that
// reading fails with a ParseError naming the file and containing a given text.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <string>

#include "metric/errors.h"
#include "metric/io/mesh_io.h"

namespace meshdev::test {

// Writes `bytes` to dir/name and returns the path.
inline std::string write_file(const std::string& dir, const std::string& name,
                              const std::string& bytes) {
  std::string path = dir + "/" + name;
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
}

// Appends the little- or big-endian bytes of `v` to `out`.
template <class T>
void put(std::string& out, T v, bool big_endian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  out.append(b, sizeof(T));
}

// read_mesh(path) must throw a ParseError whose message names the file and contains `text`.
inline void expect_parse_error(const std::string& path, const std::string& text) {
  try {
    read_mesh(path);
    ADD_FAILURE() << path << ": read without error, expected '" << text << "'";
  } catch (const ParseError& e) {
    std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(text), std::string::npos) << "expected '" << text << "' in: " << what;
  }
}

}  // namespace meshdev::test
