#include "metric/io/read_off.h"

#include <gtest/gtest.h>

#include "metric/io/mesh_io.h"
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

}  // namespace
}  // namespace meshdev::test
