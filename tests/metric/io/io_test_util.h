#pragma once
// Helpers of the reader/writer tests: tiny files written from strings or bytes, a check that
// reading fails with a ParseError naming the file and containing a given text, and the
// comparison of two parses (mesh or error) for the chunked parses' tests.
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

// --- For the chunked parses' tests: their oracle is the line-by-line parse. ---

// Everything a reader fills in, compared bit for bit.
inline void expect_same_mesh(const TriMesh& got, const TriMesh& want) {
  ASSERT_EQ(got.positions.size(), want.positions.size());
  for (std::size_t v = 0; v < got.positions.size(); ++v)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(got.positions[v][k], want.positions[v][k]) << v;
  EXPECT_EQ(got.faces, want.faces);
  EXPECT_EQ(got.source_polygons, want.source_polygons);
  EXPECT_EQ(got.source_file, want.source_file);
  EXPECT_EQ(got.texture_file, want.texture_file);
  ASSERT_EQ(got.channels.size(), want.channels.size());
  for (std::size_t c = 0; c < got.channels.size(); ++c) {
    EXPECT_EQ(got.channels[c].name, want.channels[c].name);
    EXPECT_EQ(got.channels[c].kind, want.channels[c].kind);
    EXPECT_EQ(got.channels[c].storage, want.channels[c].storage);
    EXPECT_EQ(got.channels[c].dim, want.channels[c].dim);
    EXPECT_EQ(got.channels[c].values, want.channels[c].values) << got.channels[c].name;
  }
}

// The outcome of a parse: the mesh, or the error's message.
struct Outcome {
  TriMesh mesh;
  std::string error;
};
template <class Parse>
Outcome outcome_of(Parse&& parse) {
  Outcome o;
  try {
    o.mesh = parse();
  } catch (const ParseError& e) {
    o.error = e.what();
  }
  return o;
}

// A chunked parse, chunked(chunks, threads, &used), gives what line_by_line() gives, mesh or
// error, for 2, 3, 5 and 17 chunks on 1 and 2 threads; `chunked_result`: whether the chunks'
// result must be the one returned (a valid file) rather than the line-by-line parse's (an error
// found in a chunk or between chunks).
template <class LineByLine, class Chunked>
void expect_chunks_agree(LineByLine line_by_line, Chunked chunked, bool chunked_result) {
  const Outcome want = outcome_of(line_by_line);
  EXPECT_EQ(want.error.empty(), chunked_result) << want.error;
  for (int chunks : {2, 3, 5, 17})
    for (int threads : {1, 2}) {
      SCOPED_TRACE("chunks " + std::to_string(chunks) + ", threads " + std::to_string(threads));
      bool used = false;
      const Outcome got = outcome_of([&] { return chunked(chunks, threads, &used); });
      EXPECT_EQ(got.error, want.error);
      EXPECT_EQ(used, chunked_result);
      if (want.error.empty()) expect_same_mesh(got.mesh, want.mesh);
    }
}

}  // namespace meshdev::test
