#include "metric/io/read_stl.h"

#include <gtest/gtest.h>

#include "metric/io/mesh_io.h"
#include "tests/metric/io/io_test_util.h"
#include "tests/support/test_data.h"

namespace meshdev::test {
namespace {

std::string facet(const char* a, const char* b, const char* c) {
  return std::string("facet normal 0 0 1\n outer loop\n  vertex ") + a + "\n  vertex " + b +
         "\n  vertex " + c + "\n endloop\nendfacet\n";
}

std::string binary_stl(const std::vector<std::array<float, 9>>& tris, const std::string& head,
                       std::uint32_t count) {
  std::string b = head;
  b.resize(80, ' ');
  put(b, count);
  for (const auto& t : tris) {
    for (float n : {0.f, 0.f, 1.f}) put(b, n);
    for (float x : t) put(b, x);
    put(b, std::uint16_t{0});
  }
  return b;
}

TEST(ReadStl, AsciiCornersAreMergedInOrderOfFirstAppearance) {
  std::string stl = "solid s\n" + facet("0 0 0", "1 0 0", "0 1 0") +
                    facet("1 0 0", "1 1 0", "0 1 0") + "endsolid s\n";
  TriMesh m = read_mesh(write_file(scratch_dir("stl_ascii"), "a.stl", stl));
  ASSERT_EQ(m.num_vertices(), 4u);
  ASSERT_EQ(m.num_faces(), 2u);
  EXPECT_EQ(m.faces[1], (Triangle{1, 3, 2}));
  EXPECT_EQ(m.positions[3].x, 1.0);
  EXPECT_TRUE(m.channels.empty());  // STL normals are never turned into a channel
}

TEST(ReadStl, BinaryWhoseHeaderStartsWithSolid) {
  std::vector<std::array<float, 9>> tris = {{0, 0, 0, 1, 0, 0, 0, 1, 0},
                                            {1, 0, 0, 1, 1, 0, 0, 1, 0}};
  TriMesh m =
      read_mesh(write_file(scratch_dir("stl_solid"), "b.stl", binary_stl(tris, "solid x", 2)));
  EXPECT_EQ(m.num_vertices(), 4u);
  EXPECT_EQ(m.num_faces(), 2u);
  EXPECT_TRUE(m.channels.empty());
}

TEST(ReadStl, OnlyBitIdenticalPositionsAreMerged) {
  std::vector<std::array<float, 9>> tris = {{0, 0, 0, 1, 0, 0, 0, 1, 0},
                                            {-0.f, 0, 0, 1, 0, 0, 0, 1, 1e-7f}};
  TriMesh m = read_mesh(write_file(scratch_dir("stl_bits"), "b.stl", binary_stl(tris, "x", 2)));
  EXPECT_EQ(m.num_vertices(), 5u);  // -0 and 0 differ in bits; (0,1,1e-7) is new
}

TEST(ReadStl, MalformedInputs) {
  std::string dir = scratch_dir("stl_bad");
  std::vector<std::array<float, 9>> one = {{0, 0, 0, 1, 0, 0, 0, 1, 0}};
  expect_parse_error(write_file(dir, "empty.stl", ""), "empty file");
  expect_parse_error(write_file(dir, "short.stl", std::string(40, '\1')), "too short");
  expect_parse_error(write_file(dir, "ffff.stl", binary_stl(one, "x", 0xFFFFFFFFu)),
                     "4294967295 triangles");
  std::string two = binary_stl({one[0], one[0]}, "x", 2);
  expect_parse_error(write_file(dir, "part.stl", two.substr(0, 84 + 70)),
                     "header says 2 triangles");
  expect_parse_error(write_file(dir, "zero.stl", binary_stl({}, "x", 0)), "0 triangles");
  expect_parse_error(
      write_file(dir, "nan.stl", binary_stl({{0, 0, 0, NAN, 0, 0, 0, 1, 0}}, "x", 1)),
      "face 0: corner 1 has a non-finite coordinate");
  const std::string whole = "solid s\n" + facet("0 0 0", "1 0 0", "0 1 0");
  expect_parse_error(write_file(dir, "trunc.stl", whole.substr(0, whole.find("vertex 1") + 6)),
                     "truncated");
  expect_parse_error(
      write_file(dir, "anan.stl", "solid s\n" + facet("0 0 0", "1 nan 0", "0 1 0") + "endsolid\n"),
      "line 5: 'nan' is not a finite");
  expect_parse_error(
      write_file(dir, "two.stl",
                 "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                 "endloop\nendfacet\nendsolid\n"),
      "facet with 2 vertices");
}

TEST(ReadStlReal, KnotMaxSimplifiedBinary) {
  std::string data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "shared data folder (../shared/data) not present";
  TriMesh m = read_mesh(data + "/metro_knot/knot_max_simplified.STL");
  EXPECT_EQ(m.num_vertices(), 800u);
  EXPECT_EQ(m.num_faces(), 1600u);
  EXPECT_TRUE(m.channels.empty());
}

TEST(ReadStlCgal, PigAndSphere) {
  std::string pig = cgal_mesh("pig.stl");
  if (pig.empty()) GTEST_SKIP() << "libcgal-demo data archive not installed";
  TriMesh m = read_mesh(pig);
  EXPECT_EQ(m.num_faces(), 16848u);
  EXPECT_EQ(m.num_vertices(), 8642u);
  TriMesh s = read_mesh(cgal_mesh("sphere.stl"));
  EXPECT_EQ(s.num_vertices(), 162u);
  EXPECT_EQ(s.num_faces(), 320u);
}

}  // namespace
}  // namespace meshdev::test
