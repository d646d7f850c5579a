#include "metric/io/read_obj.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "metric/io/mesh_io.h"
#include "metric/io/text_scan.h"
#include "tests/metric/io/io_test_util.h"
#include "tests/support/test_data.h"

namespace meshdev::test {
namespace {

const char* kTri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

TEST(ReadObj, TriangleWithProvenance) {
  std::string path = write_file(scratch_dir("obj_tri"), "t.obj", std::string(kTri) + "f 1 2 3\n");
  TriMesh m = read_mesh(path);
  ASSERT_EQ(m.num_vertices(), 3u);
  ASSERT_EQ(m.num_faces(), 1u);
  EXPECT_EQ(m.faces[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(m.positions[1].x, 1.0);
  EXPECT_EQ(m.source_file, path);
  EXPECT_EQ(m.source_polygons, 1u);
  EXPECT_TRUE(m.channels.empty());
}

TEST(ReadObj, QuadIsFannedFromFirstCornerAndCornersKeepTheirUVs) {
  // Vertex 1 gets vt 1 in the quad and vt 5 in the triangle: UVs must be per corner.
  std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
      "f 1/1 2/2 3/3 4/4\nf 1/5 3/3 4/4\n";
  TriMesh m = read_mesh(write_file(scratch_dir("obj_quad"), "q.obj", obj));
  ASSERT_EQ(m.num_faces(), 3u);
  EXPECT_EQ(m.source_polygons, 2u);
  EXPECT_EQ(m.faces[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(m.faces[1], (Triangle{0, 2, 3}));
  const AttributeChannel* uv = m.channel("texcoord");
  ASSERT_NE(uv, nullptr);
  EXPECT_EQ(uv->storage, Storage::kPerCorner);
  EXPECT_EQ(uv->kind, AttributeKind::kTexCoord);
  // Face 1 = corners (1, 3, 4) of the quad: UVs (0,0), (1,1), (0,1).
  EXPECT_EQ(uv->element(3 * 1 + 1)[0], 1.0);
  EXPECT_EQ(uv->element(3 * 1 + 2)[1], 1.0);
  EXPECT_EQ(uv->element(3 * 2 + 0)[0], 0.5);
}

TEST(ReadObj, ConsistentUVsAndNormalsArePerVertex) {
  std::string obj = std::string(kTri) +
                    "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 2\n"
                    "f 1/1/1 2/2/2 3/3/3\n";
  TriMesh m = read_mesh(write_file(scratch_dir("obj_pv"), "pv.obj", obj));
  ASSERT_NE(m.channel("texcoord"), nullptr);
  EXPECT_EQ(m.channel("texcoord")->storage, Storage::kPerVertex);
  ASSERT_NE(m.channel("normal"), nullptr);
  EXPECT_EQ(m.channel("normal")->storage, Storage::kPerVertex);
  EXPECT_EQ(m.channel("normal")->element(2)[2], 2.0);
}

TEST(ReadObj, UnreferencedVertexForcesPerCornerUVs) {
  std::string obj = std::string(kTri) + "v 9 9 9\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
  TriMesh m = read_mesh(write_file(scratch_dir("obj_unref"), "u.obj", obj));
  EXPECT_EQ(m.num_vertices(), 4u);
  EXPECT_EQ(m.channel("texcoord")->storage, Storage::kPerCorner);
}

TEST(ReadObj, NegativeAndForwardIndices) {
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nf 1 3 4\nv 1 1 0\n";
  TriMesh m = read_mesh(write_file(scratch_dir("obj_neg"), "n.obj", obj));
  ASSERT_EQ(m.num_faces(), 2u);
  EXPECT_EQ(m.faces[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(m.faces[1], (Triangle{0, 2, 3}));
}

TEST(ReadObj, VertexColours) {
  std::string obj = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n";
  TriMesh m = read_mesh(write_file(scratch_dir("obj_col"), "c.obj", obj));
  const AttributeChannel* c = m.channel("color");
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->kind, AttributeKind::kColor);
  EXPECT_EQ(c->element(1)[1], 1.0);
}

TEST(ReadObj, CrlfBomCommentsAndIgnoredRecords) {
  std::string obj =
      "\xEF\xBB\xBF# c\r\no thing\r\ng grp\r\ns 1\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\n"
      "l 1 2\r\nf 1 2 3 # trailing\r\n";
  TriMesh m = read_mesh(write_file(scratch_dir("obj_crlf"), "c.obj", obj));
  EXPECT_EQ(m.num_faces(), 1u);
}

TEST(ReadObj, RepeatedCornerAndUnreferencedVertexAreKept) {
  std::string obj = std::string(kTri) + "v 5 5 5\nf 1 2 2\n";
  TriMesh m = read_mesh(write_file(scratch_dir("obj_degen"), "d.obj", obj));
  EXPECT_EQ(m.num_vertices(), 4u);
  EXPECT_EQ(m.faces[0], (Triangle{0, 1, 1}));
}

TEST(ReadObj, MaterialWithWindowsPathAndMissingLibrary) {
  std::string dir = scratch_dir("obj_mtl");
  write_file(dir, "m.mtl", "newmtl a\nmap_Kd .\\a.png\nnewmtl b\nmap_Kd -s 1 1 1 .\\tex\\b.jpg\n");
  TriMesh m = read_mesh(
      write_file(dir, "m.obj", "mtllib m.mtl\n" + std::string(kTri) + "usemtl b\nf 1 2 3\n"));
  EXPECT_EQ(m.texture_file, dir + "/tex/b.jpg");
  // A missing .mtl is a warning, not an error.
  TriMesh n =
      read_mesh(write_file(dir, "n.obj", "mtllib nowhere.mtl\n" + std::string(kTri) + "f 1 2 3\n"));
  EXPECT_EQ(n.num_faces(), 1u);
  EXPECT_TRUE(n.texture_file.empty());
}

// Positive indices may name elements defined later, so they are checked after the last line;
// the error still names the line of the face that used the index (found by reading the text
// again), for vertices, texture coordinates and normals alike, and faces that reference no vt or
// vn keep none.
TEST(ReadObj, IndicesCheckedAtTheEndNameTheirFacesLine) {
  std::string dir = scratch_dir("obj_deferred");
  const TriMesh ahead = read_mesh(write_file(
      dir, "ahead.obj", "f 1 2 3\n# a comment\nf 3 2 4\n" + std::string(kTri) + "v 1 1 0\n"));
  EXPECT_EQ(ahead.num_faces(), 2u);
  EXPECT_EQ(ahead.faces[1], (Triangle{2, 1, 3}));
  EXPECT_EQ(ahead.channel("texcoord"), nullptr);
  EXPECT_EQ(ahead.channel("normal"), nullptr);
  expect_parse_error(
      write_file(dir, "v.obj", "f 1 2 3\n\nf 1 2 9\n" + std::string(kTri) + "f 1 2 3\n"),
      "line 3: vertex index 9 out of range (3 defined)");
  const std::string body = std::string(kTri) + "vt 0 0\nvn 0 0 1\n";
  expect_parse_error(write_file(dir, "vt.obj", "f 1/1/1 2/1/1 3/1/1\nf 1/1/1 2/5/1 3/1/1\n" + body),
                     "line 2: texture coordinate index 5 out of range (1 defined)");
  expect_parse_error(
      write_file(dir, "vn.obj", "f 1/1/1 2/1/1 3/1/1\ng x\nf 1/1/1 2/1/1 3/1/7\n" + body),
      "line 3: normal index 7 out of range (1 defined)");
  const TriMesh both = read_mesh(write_file(dir, "both.obj", "f 1/1/1 2/1/1 3/1/1\n" + body));
  ASSERT_NE(both.channel("texcoord"), nullptr);
  ASSERT_NE(both.channel("normal"), nullptr);
  EXPECT_EQ(both.channel("normal")->element(0)[2], 1.0);
}

TEST(ReadObj, MalformedInputsNameFileLineAndProblem) {
  std::string dir = scratch_dir("obj_bad");
  expect_parse_error(write_file(dir, "empty.obj", ""), "empty file");
  expect_parse_error(write_file(dir, "zero.obj", std::string(kTri) + "f 0 1 2\n"),
                     "line 4: vertex index 0");
  expect_parse_error(write_file(dir, "range.obj", std::string(kTri) + "f 1 2 4\n"), "out of range");
  expect_parse_error(write_file(dir, "neg.obj", std::string(kTri) + "f 1 2 -4\n"),
                     "before the first");
  expect_parse_error(write_file(dir, "two.obj", std::string(kTri) + "f 1 2\n"), "2 corners");
  expect_parse_error(write_file(dir, "nan.obj", "v 0 nan 0\n"), "line 1: 'nan' is not a finite");
  expect_parse_error(write_file(dir, "z.obj", "v 0 0\n"), "needs 3 coordinates");
  expect_parse_error(write_file(dir, "text.obj", "v 0 0 x\n"), "'x' is not a number");
  expect_parse_error(write_file(dir, "partial.obj", std::string(kTri) + "vt 0 0\nf 1/1 2/1 3\n"),
                     "differ in which of vt/vn");
  expect_parse_error(
      write_file(dir, "mixed.obj", std::string(kTri) + "vt 0 0\nf 1/1 2/1 3/1\nf 1 2 3\n"),
      "texture coordinates missing");
  expect_parse_error(write_file(dir, "kw.obj", "vertex 1 2 3\n"), "unknown OBJ keyword");
  expect_parse_error(write_file(dir, "nov.obj", "# only a comment\n"), "no vertices");
}

TEST(ReadObj, VeryLongLine) {
  std::string obj = std::string(kTri) + "f 1 2 3" + std::string(500000, ' ') + "\n";
  EXPECT_EQ(read_mesh(write_file(scratch_dir("obj_long"), "l.obj", obj)).num_faces(), 1u);
}

TEST(ReadObjReal, TexturedBunny) {
  std::string data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "shared data folder (../shared/data) not present";
  TriMesh m = read_mesh(data + "/textured/bunny10k_textured/bunny10k_textured.obj");
  EXPECT_EQ(m.num_vertices(), 5051u);
  EXPECT_EQ(m.num_faces(), 9999u);
  ASSERT_NE(m.channel("texcoord"), nullptr);
  EXPECT_EQ(m.channel("texcoord")->storage, Storage::kPerCorner);
  EXPECT_EQ(std::filesystem::path(m.texture_file).filename(), "TextureDouble_A.png");
  EXPECT_TRUE(std::filesystem::exists(m.texture_file));
}

TEST(ReadObjReal, SpiderWithWindowsMaterialPaths) {
  std::string data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "shared data folder (../shared/data) not present";
  TriMesh m = read_mesh(data + "/textured/spider/spider.obj");
  EXPECT_EQ(m.num_vertices(), 762u);
  EXPECT_EQ(m.num_faces(), 1368u);
  EXPECT_NE(m.channel("texcoord"), nullptr);
  EXPECT_NE(m.channel("normal"), nullptr);
  EXPECT_EQ(std::filesystem::path(m.texture_file).filename(), "SpiderTex.jpg");
  EXPECT_TRUE(std::filesystem::exists(m.texture_file));
}

TEST(ReadObjReal, VestaNormalsPerVertex) {
  std::string data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "shared data folder (../shared/data) not present";
  TriMesh m = read_mesh(data + "/textured/vesta/4vesta_21_MLfix.obj");
  EXPECT_EQ(m.num_vertices(), 2522u);
  EXPECT_EQ(m.num_faces(), 5040u);
  EXPECT_EQ(m.channel("normal")->storage, Storage::kPerVertex);
  EXPECT_NO_THROW(validate(m, "vesta"));
}

// Its read speed is a benchmark (bench/io/read_mesh_bench.cpp), not a unit test.
TEST(ReadObjReal, BuildingsLoads) {
  std::string data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "shared data folder (../shared/data) not present";
  TriMesh m = read_mesh(data + "/large/buildings.obj");
  EXPECT_EQ(m.num_vertices(), 200062u);
  EXPECT_EQ(m.num_faces(), 400020u);
}

// --- The chunked parse (large files on a team) against the line-by-line parse, its oracle. ---

// expect_chunks_agree for OBJ text (io_test_util.h).
void expect_obj_chunks_agree(const std::string& obj, bool chunked) {
  const std::string path = "/nonexistent/chunks.obj";  // (no mtllib here: nothing is opened)
  expect_chunks_agree([&] { return read_obj(path, obj, 1); },
                      [&](int chunks, int threads, bool* used) {
                        return detail::read_obj_in_chunks(path, obj, chunks, threads, used);
                      },
                      chunked);
}

// An n x n grid of quads with UVs and normals (one per vertex), the faces' indices alternating
// between absolute and relative (negative: counted back from the last vertex read), with
// comments, group lines, blank lines and CRLF line ends among them.
std::string grid_obj(int n, bool colors) {
  std::string obj = "# grid\r\no grid\r\n";
  const int side = n + 1;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      obj += "v " + std::to_string(x * 0.25) + " " + std::to_string(y / 3.0) + " " +
             std::to_string((x * y) % 7 * 0.01);
      if (colors) obj += " 0.5 " + std::to_string(x % 2) + " 0.25";
      obj += "\n";
      obj += "vt " + std::to_string(x / double(n)) + " " + std::to_string(y / double(n)) + "\n";
      obj += "vn 0 " + std::to_string(x % 3 * 0.1) + " 1\n";
      if ((x + y) % 13 == 0) obj += "\n# a comment\ns 1\n";
    }
  const int total = side * side;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int c[4] = {y * side + x + 1, y * side + x + 2, (y + 1) * side + x + 2,
                        (y + 1) * side + x + 1};
      obj += "f";
      for (int i : c) {
        const std::string id = (x + y) % 2 ? std::to_string(i) : std::to_string(i - total - 1);
        obj += " " + id + "/" + id + "/" + id;
      }
      obj += (x % 5 == 0 ? "\r\n" : "\n");
      if (x % 7 == 3) obj += "g part" + std::to_string(x) + "\n";
    }
  return obj;
}

TEST(ReadObj, ChunkedParseEqualsTheLineByLineParse) {
  expect_obj_chunks_agree(grid_obj(30, false), true);
  expect_obj_chunks_agree(grid_obj(20, true), true);
  // Vertices and faces interleaved, relative indices reaching back across chunks.
  std::string mixed;
  for (int i = 0; i < 400; ++i)
    mixed += "v " + std::to_string(i) + " 0 " + std::to_string(i % 3) + "\nv " + std::to_string(i) +
             " 1 0\nv " + std::to_string(i) + " 2 1\nf -3 -2 -1\n" + (i > 0 ? "f -4 -5 -2\n" : "");
  expect_obj_chunks_agree(mixed, true);
  // One line only, and a byte order mark.
  expect_obj_chunks_agree("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3", true);
}

TEST(ReadObj, ChunkedParseReportsTheLineByLineParsesError) {
  const std::string grid = grid_obj(20, false);
  // A malformed number near the end, and another one earlier: the first is named.
  std::string two_errors = grid;
  two_errors.insert(two_errors.size() / 4, "v 1 2 x\n");
  two_errors += "v 1 2 y\n";
  expect_obj_chunks_agree(two_errors, false);
  // A relative index reaching before the first vertex, far from the start of the file.
  expect_obj_chunks_agree(grid + "f -1 -2 -99999\n", false);
  // Colours on the first vertices only (the rule spans chunks).
  expect_obj_chunks_agree(grid_obj(20, true) + "v 1 2 3\n", false);
  // A face without the texture coordinates and normals of the first face.
  expect_obj_chunks_agree(grid + "f 1 2 3\n", false);
  // An absolute index beyond the last vertex (checked once all are read).
  expect_obj_chunks_agree(grid + "f 1 2 99999\n", false);
  // No vertex at all.
  std::string faces_only;
  for (int i = 0; i < 200; ++i) faces_only += "# nothing\ng x\n";
  expect_obj_chunks_agree(faces_only, false);
}

// The real OBJ files (textures, normals, polygons, the 400k-face buildings) read in chunks on two
// threads: the line-by-line parse's mesh, and the chunks' result used.
TEST(ReadObjReal, ChunkedParseEqualsTheLineByLineParse) {
  std::string data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "shared data folder (../shared/data) not present";
  for (const char* file :
       {"/large/buildings.obj", "/plain/koala.obj", "/plain/koala_low_resolution.obj",
        "/textured/bunny10k_textured/bunny10k_textured.obj", "/textured/spider/spider.obj",
        "/textured/vesta/4vesta_21_MLfix.obj"}) {
    SCOPED_TRACE(file);
    const std::string path = data + file;
    const std::string content = io_detail::read_file_bytes(path);
    bool used = false;
    const TriMesh chunked = detail::read_obj_in_chunks(path, content, 5, 2, &used);
    EXPECT_TRUE(used);
    expect_same_mesh(chunked, read_obj(path, content, 1));
  }
}

}  // namespace
}  // namespace meshdev::test
