#include "metric/io/read_off.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "metric/io/mesh_io.h"
#include "metric/io/text_scan.h"
#include "tests/metric/io/io_test_util.h"
#include "tests/support/test_data.h"

namespace meshdev::test {
namespace {

TEST(ReadOff, PolygonsCommentsAndCountsOnTheKeywordLine) {
  std::string off =
      "# leading comment\nOFF 5 2 0\n0 0 0 # a\n1 0 0\n1 1 0\n\n0 1 0\n-1 0 0\n"
      "4 0 1 2 3 # quad\n3 0 3 4 255 0 0\n";
  TriMesh m = read_mesh(write_file(scratch_dir("off_poly"), "p.off", off));
  EXPECT_EQ(m.num_vertices(), 5u);
  ASSERT_EQ(m.num_faces(), 3u);
  EXPECT_EQ(m.source_polygons, 2u);
  EXPECT_EQ(m.faces[1], (Triangle{0, 2, 3}));
  EXPECT_TRUE(m.channels.empty());
}

TEST(ReadOff, IntegerColoursAreDividedBy255AndAlphaKept) {
  std::string off =
      "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 51 0 128\n0 1 0 0 0 255 255\n3 0 1 2\n";
  TriMesh m = read_mesh(write_file(scratch_dir("off_icol"), "c.off", off));
  const AttributeChannel* c = m.channel("color");
  ASSERT_NE(c, nullptr);
  EXPECT_DOUBLE_EQ(c->element(1)[1], 0.2);
  ASSERT_NE(m.channel("alpha"), nullptr);
  EXPECT_DOUBLE_EQ(m.channel("alpha")->element(1)[0], 128.0 / 255.0);
}

TEST(ReadOff, FloatColoursAreTakenAsTheyAre) {
  std::string off = "COFF\n3 1 0\n0 0 0 1 0 0\n1 0 0 0 0.5 0\n0 1 0 0 0 1\n3 0 1 2\n";
  TriMesh m = read_mesh(write_file(scratch_dir("off_fcol"), "c.off", off));
  EXPECT_EQ(m.channel("color")->element(0)[0], 1.0);
  EXPECT_EQ(m.channel("color")->element(1)[1], 0.5);
  EXPECT_EQ(m.channel("alpha"), nullptr);
}

TEST(ReadOff, NormalsColoursAndTexcoordsTogether) {
  std::string off =
      "STCNOFF\r\n3 1 0\r\n0 0 0 0 0 1 1 0 0 0.1 0.2\r\n1 0 0 0 0 1 0 1 0 0.3 0.4\r\n"
      "0 1 0 0 0 1 0 0 1 0.5 0.6\r\n3 0 1 2\r\n";
  TriMesh m = read_mesh(write_file(scratch_dir("off_all"), "a.off", off));
  ASSERT_NE(m.channel("normal"), nullptr);
  ASSERT_NE(m.channel("color"), nullptr);
  ASSERT_NE(m.channel("texcoord"), nullptr);
  EXPECT_EQ(m.channel("texcoord")->element(2)[1], 0.6);
  EXPECT_NO_THROW(validate(m, "a.off"));
}

TEST(ReadOff, MalformedInputs) {
  std::string dir = scratch_dir("off_bad");
  const std::string tri = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  expect_parse_error(write_file(dir, "empty.off", ""), "empty file");
  expect_parse_error(write_file(dir, "binary.off", "OFF BINARY\n\x00\x00\x00\x03"),
                     "binary OFF is not supported");
  expect_parse_error(write_file(dir, "big.off", "OFF\n2000000000 1 0\n" + tri),
                     "header declares 2000000000");
  expect_parse_error(write_file(dir, "neg.off", "OFF\n-1 -1 0\n" + tri), "negative count");
  expect_parse_error(
      write_file(dir, "more.off", "OFF\n3 2 0\n" + tri + "# padding padding padding\n"),
      "file ends after 1 of 2 faces");
  expect_parse_error(write_file(dir, "less.off", "OFF\n3 1 0\n" + tri + "3 2 1 0\n"),
                     "line 7: extra data");
  expect_parse_error(write_file(dir, "idx.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
                     "face 0: vertex index 3 out of range");
  expect_parse_error(write_file(dir, "two.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1   #pad\n"),
                     "2 corners");
  expect_parse_error(write_file(dir, "nan.off", "OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n"),
                     "line 4: vertex 1: 'nan'");
  expect_parse_error(write_file(dir, "val.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1000000 0 1 2\n"),
                     "declares 1000000 corners");
  expect_parse_error(write_file(dir, "kw.off", "3 1 0\n" + tri), "expected an OFF keyword");
  // Each bad token is named by what it should have been.
  const std::string three = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
  expect_parse_error(write_file(dir, "cnt.off", "OFF\n3 x 0\n"), "count: 'x' is not an integer");
  expect_parse_error(write_file(dir, "cc.off", three + "q 0 1 2\n"),
                     "line 6: face 0 corner count: 'q' is not an integer");
  expect_parse_error(write_file(dir, "ix.off", three + "3 0 1 2.5\n"),
                     "line 6: face 0 index: '2.5' is not an integer");
  expect_parse_error(write_file(dir, "col.off", three + "3 0 1 2 1 zz 1\n"),
                     "line 6: face 0 colour: 'zz' is not a number");
}

TEST(ReadOffReal, DinoAndElephant) {
  std::string data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "shared data folder (../shared/data) not present";
  TriMesh dino = read_mesh(data + "/colors/dino.off");
  EXPECT_EQ(dino.num_vertices(), 3916u);
  EXPECT_EQ(dino.num_faces(), 7828u);
  ASSERT_NE(dino.channel("color"), nullptr);
  EXPECT_DOUBLE_EQ(dino.channel("color")->element(0)[0], 192.0 / 255.0);
  TriMesh elephant = read_mesh(data + "/plain/elephant.off");
  EXPECT_EQ(elephant.num_vertices(), 2775u);
  EXPECT_EQ(elephant.num_faces(), 5558u);
  TriMesh abominable = read_mesh(data + "/problematic/abominevole.off");
  EXPECT_EQ(abominable.num_vertices(), 5021u);
  EXPECT_EQ(abominable.num_faces(), 50706u);
}

TEST(ReadOffCgal, MeshWithColoursAndBunny) {
  std::string path = cgal_mesh("mesh_with_colors.off");
  if (path.empty()) GTEST_SKIP() << "libcgal-demo data archive not installed";
  TriMesh m = read_mesh(path);
  EXPECT_EQ(m.num_vertices(), 8u);
  EXPECT_EQ(m.source_polygons, 4u);
  EXPECT_EQ(m.num_faces(), 6u);
  EXPECT_DOUBLE_EQ(m.channel("color")->element(0)[0], 0.9);
  TriMesh bunny = read_mesh(cgal_mesh("bunny00.off"));
  EXPECT_EQ(bunny.num_vertices(), 37706u);
  EXPECT_EQ(bunny.num_faces(), 75408u);
}

// --- The chunked parse (large files on a team) against the line-by-line parse, its oracle. ---

// expect_chunks_agree for OFF text (io_test_util.h).
void expect_off_chunks_agree(const std::string& off, bool chunked) {
  const std::string path = "chunks.off";
  expect_chunks_agree([&] { return read_off(path, off, 1); },
                      [&](int chunks, int threads, bool* used) {
                        return detail::read_off_in_chunks(path, off, chunks, threads, used);
                      },
                      chunked);
}

// A grid of n x n quads (some written as two triangles, some with a face colour), with comments
// and blank lines between records; `keyword` decides the vertex lines' values (C: integer RGB,
// or float RGB where `float_colors`; N: normals; ST: texture coordinates).
std::string grid_off(int n, const std::string& keyword, bool float_colors = false) {
  const int side = n + 1;
  std::string records;
  int faces = 0;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      records += std::to_string(x * 0.5) + " " + std::to_string(y / 3.0) + " 0";
      if (keyword.find('N') != std::string::npos) records += " 0 0 1";
      if (keyword.find('C') != std::string::npos)
        records += float_colors ? " 0.5 0.25 " + std::to_string((x % 4) / 4.0)
                                : " 255 " + std::to_string(x % 256) + " 7";
      if (keyword.find("ST") != std::string::npos)
        records += " " + std::to_string(x / double(n)) + " 0.5";
      records += (x + y) % 11 == 0 ? "   # vertex\n\n" : "\n";
    }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * side + x, b = a + 1, c = a + side + 1, d = a + side;
      if ((x + y) % 3 == 0) {
        records += "3 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) +
                   "\n3 " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) +
                   " 255 0 0\n";
        faces += 2;
      } else {
        records += "4 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) +
                   " " + std::to_string(d) + (x % 7 == 0 ? " # quad\r\n" : "\n");
        faces += 1;
      }
    }
  return "# grid\n" + keyword + "\n" + std::to_string(side * side) + " " + std::to_string(faces) +
         " 0\n" + records;
}

TEST(ReadOff, ChunkedParseEqualsTheLineByLineParse) {
  expect_off_chunks_agree(grid_off(30, "OFF"), true);
  expect_off_chunks_agree(grid_off(20, "COFF"), true);
  expect_off_chunks_agree(grid_off(20, "COFF", true), true);
  expect_off_chunks_agree(grid_off(20, "STCNOFF"), true);
  // The counts on the keyword line, a byte order mark, a single record of each kind.
  expect_off_chunks_agree("\xEF\xBB\xBFOFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2", true);
}

TEST(ReadOff, ChunkedParseReportsTheLineByLineParsesError) {
  const std::string grid = grid_off(20, "OFF");
  // A malformed number early and one late: the first is named.
  std::string two_errors = grid;
  two_errors.insert(two_errors.find("\n1 ", two_errors.size() / 3) + 1, "0 x 0\n");
  two_errors.insert(two_errors.size() - 2, " y");
  expect_off_chunks_agree(two_errors, false);
  // One record too many, one too few (the file ends early).
  expect_off_chunks_agree(grid + "3 0 1 2\n", false);
  expect_off_chunks_agree(grid.substr(0, grid.rfind("\n", grid.size() - 2) + 1), false);
  // An index out of range in the last face.
  std::string bad_index = grid;
  bad_index.replace(bad_index.rfind(' ') + 1, std::string::npos, "99999\n");
  expect_off_chunks_agree(bad_index, false);
  // RGB colours up to the first vertex of the second of two chunks, RGBA from there on: each
  // chunk agrees with itself, so only the check that spans chunks finds it. Every vertex line
  // has the same length (RGB ones padded with spaces), so where the chunks are cut (about half
  // of the records' bytes, moved on to a line start) does not depend on where RGBA begins.
  {
    const int n = 1000;
    std::string faces;
    for (int i = 0; i + 2 < n; ++i)
      faces += "3 " + std::to_string(i) + " " + std::to_string(i + 1) + " " +
               std::to_string(i + 2) + "\n";
    const std::string header = "COFF\n" + std::to_string(n) + " " + std::to_string(n - 2) + " 0\n";
    auto vertex = [](int i, bool alpha) {
      char line[64];
      std::snprintf(line, sizeof line, "%04d.5 %04d.25 0 200 100 50 %s\n", i, i % 97,
                    alpha ? "255" : "   ");
      return std::string(line);
    };
    const std::size_t length = vertex(0, false).size(), records = n * length + faces.size();
    const std::size_t first_rgba = (records / 2 + length - 1) / length;  // the second chunk's
    ASSERT_LT(first_rgba, static_cast<std::size_t>(n));
    std::string mixed = header;
    for (int i = 0; i < n; ++i) mixed += vertex(i, static_cast<std::size_t>(i) >= first_rgba);
    expect_off_chunks_agree(mixed + faces, false);
  }
  std::string colours = grid_off(20, "COFF");
  const std::size_t faces = colours.find("\n3 ", colours.find(" 0\n") + 3);
  const std::size_t last_vertex = colours.rfind('\n', colours.rfind('\n', faces) - 1);
  std::string over = colours;
  over.insert(colours.find('\n', last_vertex + 1), "00");  // 7 -> 700
  expect_off_chunks_agree(over, false);
}

// The real OFF files of ../shared/data and CGAL's data read in chunks on two threads: the
// line-by-line parse's mesh, and the chunks' result used.
TEST(ReadOffReal, ChunkedParseEqualsTheLineByLineParse) {
  std::vector<std::string> paths;
  const std::string data = shared_data_dir();
  if (!data.empty())
    for (const char* f : {"/plain/armadillo.off", "/plain/elephant.off", "/plain/fandisk.off",
                          "/colors/dino.off", "/problematic/abominevole.off"})
      paths.push_back(data + f);
  for (const char* name : {"bunny00.off", "mesh_with_colors.off"})
    if (const std::string p = cgal_mesh(name); !p.empty()) paths.push_back(p);
  if (paths.empty()) GTEST_SKIP() << "neither ../shared/data nor libcgal-demo's data present";
  for (const std::string& path : paths) {
    SCOPED_TRACE(path);
    const std::string content = io_detail::read_file_bytes(path);
    bool used = false;
    const TriMesh chunked = detail::read_off_in_chunks(path, content, 5, 2, &used);
    EXPECT_TRUE(used);
    expect_same_mesh(chunked, read_off(path, content, 1));
  }
}

}  // namespace
}  // namespace meshdev::test
