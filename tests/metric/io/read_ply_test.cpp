#include "metric/io/read_ply.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include "metric/io/mesh_io.h"
#include "tests/metric/io/io_test_util.h"
#include "tests/support/test_data.h"

namespace meshdev::test {
namespace {

std::string header(const std::string& format, const std::string& vertex_props, int vertices,
                   const std::string& face_props, int faces, const std::string& extra = "") {
  return "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(vertices) + "\n" +
         vertex_props + "element face " + std::to_string(faces) + "\n" + face_props + extra +
         "end_header\n";
}
const char* kXyz = "property float x\nproperty float y\nproperty float z\n";
const char* kIdx = "property list uchar int vertex_indices\n";

TEST(ReadPly, AsciiWithNormalsColoursUVsAndScalars) {
  std::string ply = header("ascii",
                           "property double x\nproperty double y\nproperty double z\n"
                           "property float nx\nproperty float ny\nproperty float nz\n"
                           "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                           "property uchar alpha\nproperty float u\nproperty float v\n"
                           "property float quality\nproperty int temperature\n",
                           3, kIdx, 1) +
                    "0 0 0 0 0 1 255 0 0 255 0 0 0.5 20\n"
                    "1 0 0 0 0 1 0 255 0 128 1 0 1.5 21\n"
                    "0.1 1 0 0 0 1 0 0 51 0 0 1 2.5 22\n"
                    "3 0 1 2\n";
  TriMesh m = read_mesh(write_file(scratch_dir("ply_attrs"), "a.ply", ply));
  ASSERT_EQ(m.num_vertices(), 3u);
  EXPECT_EQ(m.positions[2].x, 0.1);  // double precision kept
  ASSERT_NE(m.channel("normal"), nullptr);
  EXPECT_EQ(m.channel("normal")->kind, AttributeKind::kNormal);
  const AttributeChannel* c = m.channel("color");
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->dim, 3);
  EXPECT_DOUBLE_EQ(c->element(2)[2], 0.2);
  ASSERT_NE(m.channel("alpha"), nullptr);
  EXPECT_DOUBLE_EQ(m.channel("alpha")->element(1)[0], 128.0 / 255.0);
  const AttributeChannel* uv = m.channel("texcoord");
  ASSERT_NE(uv, nullptr);
  EXPECT_EQ(uv->storage, Storage::kPerVertex);
  EXPECT_EQ(uv->element(1)[0], 1.0);
  ASSERT_NE(m.channel("quality"), nullptr);
  EXPECT_EQ(m.channel("quality")->kind, AttributeKind::kScalar);
  EXPECT_EQ(m.channel("quality")->element(2)[0], 2.5);
  ASSERT_NE(m.channel("temperature"), nullptr);
  EXPECT_EQ(m.channel("temperature")->element(0)[0], 20.0);
  EXPECT_NO_THROW(validate(m, "a.ply"));
}

TEST(ReadPly, FloatColoursAreTakenAsTheyAre) {
  std::string ply =
      header("ascii",
             std::string(kXyz) + "property float red\nproperty float green\nproperty float blue\n",
             3, kIdx, 1) +
      "0 0 0 0.25 0.5 1\n1 0 0 0 0 0\n0 1 0 1 1 1\n3 0 1 2\n";
  TriMesh m = read_mesh(write_file(scratch_dir("ply_fcol"), "f.ply", ply));
  EXPECT_EQ(m.channel("color")->element(0)[0], 0.25);
  EXPECT_EQ(m.channel("alpha"), nullptr);
}

// The same mesh in ascii, binary little-endian and binary big-endian, with every scalar type
// and unusual list count/item types, and an unknown element with a list in the middle.
std::string typed_ply(const std::string& format) {
  const bool big = format == "binary_big_endian";
  std::string props =
      "property char x\nproperty int16 y\nproperty double z\nproperty uchar a\n"
      "property ushort b\nproperty uint32 c\nproperty int32 d\nproperty float32 e\n"
      "property uint8 f\nproperty float64 g\n";
  std::string extra = "element material 1\nproperty list int float stuff\nproperty float k\n";
  std::string h = "ply\nformat " + format + " 1.0\ncomment all types\nelement vertex 4\n" + props +
                  extra +
                  "element face 2\nproperty list ushort uint vertex_indices\n"
                  "property short label\nend_header\n";
  if (format == "ascii") {
    return h +
           "0 0 0 1 2 3 -4 0.5 6 7.25\n1 0 0 1 2 3 -4 0.5 6 7.25\n0 1 0 1 2 3 -4 0.5 6 7.25\n"
           "-1 -1 0.5 255 65535 4294967295 -2147483648 1e-3 255 -1e300\n"
           "3 1.5 2.5 -3 9\n"
           "3 0 1 2 -7\n3 0 2 3 8\n";
  }
  std::string b = h;
  auto vertex = [&](std::int8_t x, std::int16_t y, double z, std::uint8_t a, std::uint16_t bb,
                    std::uint32_t c, std::int32_t d, float e, std::uint8_t f, double g) {
    put(b, x, big), put(b, y, big), put(b, z, big), put(b, a, big), put(b, bb, big);
    put(b, c, big), put(b, d, big), put(b, e, big), put(b, f, big), put(b, g, big);
  };
  vertex(0, 0, 0, 1, 2, 3, -4, 0.5f, 6, 7.25);
  vertex(1, 0, 0, 1, 2, 3, -4, 0.5f, 6, 7.25);
  vertex(0, 1, 0, 1, 2, 3, -4, 0.5f, 6, 7.25);
  vertex(-1, -1, 0.5, 255, 65535, 4294967295u, -2147483647 - 1, 1e-3f, 255, -1e300);
  put(b, std::int32_t{3}, big), put(b, 1.5f, big), put(b, 2.5f, big), put(b, -3.0f, big);
  put(b, 9.0f, big);
  for (auto face : {std::array<std::uint32_t, 3>{0, 1, 2}, std::array<std::uint32_t, 3>{0, 2, 3}}) {
    put(b, std::uint16_t{3}, big);
    for (std::uint32_t i : face) put(b, i, big);
    put(b, std::int16_t(face[2] == 2 ? -7 : 8), big);
  }
  return b;
}

TEST(ReadPly, AllTypesAndEndiannessGiveTheSameMesh) {
  std::string dir = scratch_dir("ply_types");
  TriMesh a = read_mesh(write_file(dir, "a.ply", typed_ply("ascii")));
  TriMesh le = read_mesh(write_file(dir, "le.ply", typed_ply("binary_little_endian")));
  TriMesh be = read_mesh(write_file(dir, "be.ply", typed_ply("binary_big_endian")));
  for (const TriMesh* m : {&a, &le, &be}) {
    ASSERT_EQ(m->num_vertices(), 4u);
    ASSERT_EQ(m->num_faces(), 2u);
    EXPECT_EQ(m->positions[3].x, -1.0);
    EXPECT_EQ(m->positions[3].z, 0.5);
    EXPECT_EQ(m->faces[1], (Triangle{0, 2, 3}));
    EXPECT_EQ(m->channel("c")->element(3)[0], 4294967295.0);
    EXPECT_EQ(m->channel("d")->element(3)[0], -2147483648.0);
    EXPECT_EQ(m->channel("g")->element(3)[0], -1e300);
    EXPECT_FLOAT_EQ(static_cast<float>(m->channel("e")->element(3)[0]), 1e-3f);
    const AttributeChannel* label = m->channel("label");
    ASSERT_NE(label, nullptr);
    EXPECT_EQ(label->storage, Storage::kPerFace);
    EXPECT_EQ(label->element(0)[0], -7.0);
    EXPECT_EQ(m->channel("k"), nullptr);  // properties of unknown elements are not read
  }
}

TEST(ReadPly, PolygonWithWedgeUVsIsFannedAndKeepsCornerUVs) {
  std::string ply =
      header("ascii", kXyz, 4, std::string(kIdx) + "property list uchar float texcoord\n", 1, "") +
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 8 0 0 0.1 0 0.2 0.2 0 0.3\n";
  TriMesh m = read_mesh(write_file(scratch_dir("ply_wedge"), "w.ply", ply));
  ASSERT_EQ(m.num_faces(), 2u);
  EXPECT_EQ(m.source_polygons, 1u);
  const AttributeChannel* uv = m.channel("texcoord");
  ASSERT_NE(uv, nullptr);
  EXPECT_EQ(uv->storage, Storage::kPerCorner);
  // Triangle 1 = corners 0, 2, 3.
  EXPECT_EQ(uv->element(3)[0], 0.0);
  EXPECT_EQ(uv->element(4)[0], 0.2);
  EXPECT_EQ(uv->element(5)[1], 0.3);
}

TEST(ReadPly, FaceScalarsAndColoursBecomePerFaceChannels) {
  std::string ply = header("ascii", std::string(kXyz) + "property int flags\n", 3,
                           std::string(kIdx) +
                               "property int flags\nproperty uchar red\n"
                               "property uchar green\nproperty uchar blue\n",
                           1) +
                    "0 0 0 1\n1 0 0 2\n0 1 0 3\n3 0 1 2 5 255 0 0\n";
  TriMesh m = read_mesh(write_file(scratch_dir("ply_face"), "f.ply", ply));
  ASSERT_NE(m.channel("flags"), nullptr);
  EXPECT_EQ(m.channel("flags")->storage, Storage::kPerVertex);
  ASSERT_NE(m.channel("face_flags"), nullptr);
  EXPECT_EQ(m.channel("face_flags")->element(0)[0], 5.0);
  ASSERT_NE(m.channel("color"), nullptr);
  EXPECT_EQ(m.channel("color")->storage, Storage::kPerFace);
  EXPECT_EQ(m.channel("color")->element(0)[0], 1.0);
}

TEST(ReadPly, TextureFileCommentPointCloudBomAndCrlf) {
  std::string dir = scratch_dir("ply_misc");
  std::string ply =
      "\xEF\xBB\xBFply\r\nformat ascii 1.0\r\ncomment TextureFile tex.png\r\n"
      "element vertex 2\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\n"
      "element face 0\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
      "0 0 0\r\n1 1 1\r\n";
  TriMesh m = read_mesh(write_file(dir, "p.ply", ply));
  EXPECT_EQ(m.num_vertices(), 2u);
  EXPECT_EQ(m.num_faces(), 0u);
  EXPECT_EQ(m.texture_file, dir + "/tex.png");
}

TEST(ReadPly, MalformedInputs) {
  std::string dir = scratch_dir("ply_bad");
  const std::string tri = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  expect_parse_error(write_file(dir, "noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"),
                     "end_header");
  expect_parse_error(
      write_file(dir, "noz.ply",
                 header("ascii", "property float x\nproperty float y\n", 3, kIdx, 1) + tri),
      "no scalar property 'z'");
  expect_parse_error(
      write_file(dir, "more.ply", header("ascii", kXyz, 3, kIdx, 2) + tri + "       \n"),
      "file ends after 1 of 2 face");
  expect_parse_error(
      write_file(dir, "less.ply", header("ascii", kXyz, 3, kIdx, 1) + tri + "3 0 1 2\n"),
      "extra data");
  expect_parse_error(
      write_file(dir, "idx.ply",
                 header("ascii", kXyz, 3, kIdx, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
      "line 13: face 0: vertex index 3 out of range");
  expect_parse_error(
      write_file(dir, "nan.ply",
                 header("ascii", kXyz, 3, kIdx, 1) + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"),
      "line 11: vertex 1 y: 'nan'");
  expect_parse_error(
      write_file(dir, "type.ply", header("ascii", "property flt x\n", 3, kIdx, 1) + tri),
      "unknown PLY type 'flt'");
  expect_parse_error(write_file(dir, "fmt.ply", header("binary", kXyz, 3, kIdx, 1) + tri),
                     "unknown PLY format");
  expect_parse_error(write_file(dir, "two.ply",
                                header("ascii", kXyz, 3, kIdx, 1) + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n"),
                     "2 corners");
  expect_parse_error(
      write_file(
          dir, "uvcount.ply",
          header("ascii", kXyz, 3, std::string(kIdx) + "property list uchar float texcoord\n", 1) +
              "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 4 0 0 0 0\n"),
      "texcoord list has 4 values, expected 6");
  // Binary: huge counts fail at once, before any allocation.
  std::string v3;
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(v3, f);
  std::string f1;
  put(f1, std::uint8_t{3}), put(f1, 0), put(f1, 1), put(f1, 2);
  auto t0 = std::chrono::steady_clock::now();
  expect_parse_error(
      write_file(dir, "huge.ply",
                 header("binary_little_endian", kXyz, 2147483647, kIdx, 1) + v3 + f1),
      "declares 2147483647 records");
  expect_parse_error(
      write_file(dir, "hugef.ply",
                 header("binary_little_endian", kXyz, 3, kIdx, 2147483647) + v3 + f1),
      "declares 2147483647 records");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
  expect_parse_error(
      write_file(dir, "trunc.ply",
                 header("binary_little_endian", kXyz, 3, kIdx, 1) + v3 + f1.substr(0, 9)),
      "runs past the end");
  expect_parse_error(write_file(dir, "extra.ply",
                                header("binary_little_endian", kXyz, 3, kIdx, 1) + v3 + f1 + "xx"),
                     "2 bytes of extra data");
  std::string f255 = f1;
  f255[0] = '\xff';
  expect_parse_error(
      write_file(dir, "l255.ply", header("binary_little_endian", kXyz, 3, kIdx, 1) + v3 + f255),
      "255 items runs past the end");
}

// Binary files are read by a fast loop for the usual layouts (scalar vertex properties; faces of
// one index list) that hands a malformed record to the generic loop: the mesh must equal the
// ascii twin's (read by the generic loop alone), and a bad record after good ones must give the
// generic loop's message at the same byte.
TEST(ReadPly, BinaryFastPathAgreesWithTheGenericLoop) {
  std::string dir = scratch_dir("ply_fast");
  const std::string ascii_body =
      "0 0 0 0.5\n1 0 0 -2\n1 1 0 3.25\n0 1 0 1e-30\n3 0 1 2\n4 0 1 2 3\n3 3 2 1\n";
  const std::string props = std::string(kXyz) + "property double q\n";
  std::string vertices;
  const double q[4] = {0.5, -2, 3.25, 1e-30};
  const float xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int v = 0; v < 4; ++v) put(vertices, xy[v][0]), put(vertices, xy[v][1]), put(vertices, 0.f);
  auto vertices_with_q = [&](double q1) {
    std::string b;
    for (int v = 0; v < 4; ++v) {
      put(b, xy[v][0]), put(b, xy[v][1]), put(b, 0.f);
      put(b, v == 1 ? q1 : q[v]);
    }
    return b;
  };
  // Faces {0 1 2}, {0 1 2 3}, then `last` (count first), as uchar + int or uchar + uint.
  auto faces = [](const std::vector<std::int64_t>& last, bool unsigned_items) {
    std::string b;
    for (const std::vector<std::int64_t>& f :
         {std::vector<std::int64_t>{0, 1, 2}, std::vector<std::int64_t>{0, 1, 2, 3}, last}) {
      put(b, static_cast<std::uint8_t>(f.size()));
      for (std::int64_t i : f)
        unsigned_items ? put(b, static_cast<std::uint32_t>(i))
                       : put(b, static_cast<std::int32_t>(i));
    }
    return b;
  };
  const TriMesh twin =
      read_mesh(write_file(dir, "a.ply", header("ascii", props, 4, kIdx, 3) + ascii_body));
  for (bool unsigned_items : {false, true}) {
    const std::string idx = unsigned_items ? "property list uchar uint vertex_indices\n" : kIdx;
    const std::string h = header("binary_little_endian", props, 4, idx, 3);
    const TriMesh m = read_mesh(
        write_file(dir, "b.ply", h + vertices_with_q(-2) + faces({3, 2, 1}, unsigned_items)));
    ASSERT_EQ(m.num_vertices(), twin.num_vertices());
    for (std::size_t v = 0; v < 4; ++v) EXPECT_EQ(m.positions[v], twin.positions[v]);
    EXPECT_EQ(m.faces, twin.faces);
    EXPECT_EQ(m.source_polygons, 3u);
    EXPECT_EQ(m.channel("q")->values, twin.channel("q")->values);

    // Face 2 is bad, after two good faces: the generic loop's message, at the generic loop's byte
    // (just after the value that is wrong).
    const std::size_t faces_at = h.size() + 4 * (12 + 8);
    const std::string bad_index = h + vertices_with_q(-2) + faces({3, 2, 4}, unsigned_items);
    expect_parse_error(write_file(dir, "i.ply", bad_index),
                       "byte " + std::to_string(faces_at + 13 + 17 + 1 + 12) +
                           ": face 2: vertex index 4 out of range (4 vertices)");
    expect_parse_error(
        write_file(dir, "n.ply", h + vertices_with_q(-2) + faces({3, 2}, unsigned_items)),
        "byte " + std::to_string(faces_at + 13 + 17 + 1) + ": face 2: 2 corners");
    std::string cut = h + vertices_with_q(-2) + faces({3, 2, 1}, unsigned_items);
    cut.resize(cut.size() - 2);
    expect_parse_error(write_file(dir, "t.ply", cut), "face 2: list 'vertex_indices' of 3 items");
  }
  const std::string h = header("binary_little_endian", props, 4, kIdx, 3);
  expect_parse_error(
      write_file(
          dir, "nan.ply",
          h + vertices_with_q(std::numeric_limits<double>::infinity()) + faces({3, 2, 1}, false)),
      "byte " + std::to_string(h.size() + 20 + 20) + ": vertex 1: property 'q' is not finite");
  std::string short_vertices = h + vertices_with_q(-2);
  short_vertices.resize(h.size() + 3 * 20 + 10);
  expect_parse_error(write_file(dir, "sv.ply", short_vertices), "declares 4 records");
}

// Binary files whose faces are all triangles (uchar count, int or uint indices) are read into
// the faces directly; x, y, z floats first at once. The mesh, the polygon count and every error
// (its message and byte) are the generic loop's, wherever the first odd record lies.
TEST(ReadPly, TriangleAndXyzFastPathsAgreeWithTheGenericLoop) {
  std::string dir = scratch_dir("ply_triangles");
  const float xyz[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.5f}, {2, 0, 1}};
  auto vertices = [&](float x2) {
    std::string b;
    for (int v = 0; v < 5; ++v)
      for (int k = 0; k < 3; ++k) put(b, v == 2 && k == 0 ? x2 : xyz[v][k]);
    return b;
  };
  auto faces = [](const std::vector<std::vector<std::int64_t>>& list, bool unsigned_items) {
    std::string b;
    for (const std::vector<std::int64_t>& f : list) {
      put(b, static_cast<std::uint8_t>(f.size()));
      for (std::int64_t i : f)
        unsigned_items ? put(b, static_cast<std::uint32_t>(i))
                       : put(b, static_cast<std::int32_t>(i));
    }
    return b;
  };
  auto ascii = [&](const std::vector<std::vector<std::int64_t>>& list) {
    std::string body;
    for (const auto& v : xyz)
      body += std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
    for (const auto& f : list) {
      body += std::to_string(f.size());
      for (std::int64_t i : f) body += " " + std::to_string(i);
      body += "\n";
    }
    return read_mesh(write_file(
        dir, "twin.ply", header("ascii", kXyz, 5, kIdx, static_cast<int>(list.size())) + body));
  };
  const std::vector<std::vector<std::vector<std::int64_t>>> layouts = {
      {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}},        // triangles only
      {{0, 1, 2}, {0, 1, 2, 3}, {1, 4, 2}},     // a quad after a triangle
      {{0, 1, 2, 3}, {1, 4, 2}, {0, 2, 3}},     // a quad first
      {{0, 1, 2}, {0, 2, 3}, {0, 1, 4, 2, 3}},  // a pentagon last
  };
  for (bool unsigned_items : {false, true}) {
    const std::string idx = unsigned_items ? "property list uchar uint vertex_indices\n" : kIdx;
    for (const auto& layout : layouts) {
      const TriMesh twin = ascii(layout);
      const std::string h =
          header("binary_little_endian", kXyz, 5, idx, static_cast<int>(layout.size()));
      const TriMesh m = read_mesh(
          write_file(dir, "b.ply", h + vertices(xyz[2][0]) + faces(layout, unsigned_items)));
      EXPECT_EQ(m.positions, twin.positions);
      EXPECT_EQ(m.faces, twin.faces);
      EXPECT_EQ(m.source_polygons, layout.size());
    }
    // The second triangle is bad: the generic loop's message at its byte (after the bad value).
    const std::string h = header("binary_little_endian", kXyz, 5, idx, 3);
    const std::size_t faces_at = h.size() + 5 * 12;
    const std::int64_t bad[] = {5, -1, 2147483648};
    for (const std::int64_t index : bad) {
      const std::string text =
          unsigned_items || index < 0
              ? std::to_string(unsigned_items && index < 0 ? 4294967295 : index)
              : std::to_string(static_cast<std::int32_t>(index));
      expect_parse_error(
          write_file(dir, "i.ply",
                     h + vertices(xyz[2][0]) +
                         faces({{0, 1, 2}, {0, index, 3}, {1, 4, 2}}, unsigned_items)),
          "byte " + std::to_string(faces_at + 13 + 1 + 8) + ": face 1: vertex index " + text +
              " out of range (5 vertices)");
    }
    expect_parse_error(
        write_file(dir, "n.ply",
                   h + vertices(xyz[2][0]) + faces({{0, 1, 2}, {0, 1}, {1, 4, 2}}, unsigned_items)),
        "byte " + std::to_string(faces_at + 13 + 1) + ": face 1: 2 corners");
  }
  const std::string h = header("binary_little_endian", kXyz, 5, kIdx, 1);
  expect_parse_error(
      write_file(dir, "nan.ply",
                 h + vertices(std::numeric_limits<float>::quiet_NaN()) + faces({{0, 1, 2}}, false)),
      "byte " + std::to_string(h.size() + 2 * 12 + 4) + ": vertex 2: property 'x' is not finite");
}

TEST(ReadPlyReal, StanfordBunnyWithScannerScalars) {
  std::string data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "shared data folder (../shared/data) not present";
  TriMesh m = read_mesh(data + "/scalar/stanford_bunny/bun_zipper.ply");
  EXPECT_EQ(m.num_vertices(), 35947u);
  EXPECT_EQ(m.num_faces(), 69451u);
  ASSERT_NE(m.channel("confidence"), nullptr);
  ASSERT_NE(m.channel("intensity"), nullptr);
  EXPECT_EQ(m.channel("confidence")->storage, Storage::kPerVertex);
  EXPECT_NO_THROW(validate(m, "bun_zipper"));
}

TEST(ReadPlyReal, ColoredAirplane) {
  std::string data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "shared data folder (../shared/data) not present";
  TriMesh m = read_mesh(data + "/colors/colored_airplane.ply");
  EXPECT_EQ(m.num_vertices(), 7017u);
  EXPECT_EQ(m.num_faces(), 10796u);
  const AttributeChannel* c = m.channel("color");
  ASSERT_NE(c, nullptr);
  for (double v : c->values) ASSERT_TRUE(v >= 0.0 && v <= 1.0);
  const AttributeChannel* q = m.channel("quality");
  ASSERT_NE(q, nullptr);
  double max_q = 0;
  for (double v : q->values) max_q = std::max(max_q, v);
  EXPECT_NEAR(max_q, 1.54, 0.01);
}

TEST(ReadPlyReal, TexturedBunnyWedgeUVsMatchTheObj) {
  std::string data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "shared data folder (../shared/data) not present";
  const std::string dir = data + "/textured/bunny10k_textured/";
  TriMesh ply = read_mesh(dir + "bunny10k_textured.ply");
  EXPECT_EQ(ply.num_vertices(), 5051u);
  EXPECT_EQ(ply.num_faces(), 9999u);
  const AttributeChannel* uv = ply.channel("texcoord");
  ASSERT_NE(uv, nullptr);
  EXPECT_EQ(uv->storage, Storage::kPerCorner);
  EXPECT_EQ(uv->values.size(), 9999u * 6);
  EXPECT_EQ(std::filesystem::path(ply.texture_file).filename(), "TextureDouble_A.png");
  TriMesh obj = read_mesh(dir + "bunny10k_textured.obj");
  ASSERT_EQ(obj.faces, ply.faces);
  const AttributeChannel* ouv = obj.channel("texcoord");
  double worst = 0;
  for (std::size_t i = 0; i < uv->values.size(); ++i)
    worst = std::max(worst, std::abs(uv->values[i] - ouv->values[i]));
  EXPECT_LT(worst, 1e-4);
}

TEST(ReadPlyReal, KnotFlagsAndMetroQuality) {
  std::string data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "shared data folder (../shared/data) not present";
  TriMesh knot = read_mesh(data + "/metro_knot/knot_orig.ply");
  EXPECT_EQ(knot.num_vertices(), 12800u);
  EXPECT_EQ(knot.num_faces(), 25600u);
  EXPECT_NE(knot.channel("flags"), nullptr);
  TriMesh metro = read_mesh(data + "/metro_knot/knot_vcg_simplified_metro.ply");
  EXPECT_EQ(metro.num_vertices(), 800u);
  EXPECT_NE(metro.channel("quality"), nullptr);
  EXPECT_NE(metro.channel("color"), nullptr);
}

TEST(ReadPlyCgal, ColoredTetraWithEdgesAndSphere) {
  std::string tetra = cgal_mesh("colored_tetra.ply");
  if (tetra.empty()) GTEST_SKIP() << "libcgal-demo data archive not installed";
  TriMesh m = read_mesh(tetra);
  EXPECT_EQ(m.num_vertices(), 4u);
  EXPECT_EQ(m.num_faces(), 4u);
  EXPECT_NE(m.channel("normal"), nullptr);
  EXPECT_EQ(m.channel("color")->storage, Storage::kPerVertex);
  EXPECT_DOUBLE_EQ(m.channel("color")->element(2)[0], 128.0 / 255.0);
  EXPECT_NE(m.channel("face_color"), nullptr);
  TriMesh s = read_mesh(cgal_mesh("sphere.ply"));
  EXPECT_EQ(s.num_vertices(), 162u);
  EXPECT_EQ(s.num_faces(), 320u);
}

}  // namespace
}  // namespace meshdev::test
