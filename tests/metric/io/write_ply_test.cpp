#include "metric/io/write_ply.h"

#include <gtest/gtest.h>

#include "metric/io/mesh_io.h"
#include "metric/io/write_obj.h"
#include "tests/metric/io/io_test_util.h"
#include "tests/support/shapes.h"
#include "tests/support/test_data.h"

namespace meshdev::test {
namespace {

// A tetrahedron with awkward doubles and one channel of every per-vertex kind.
TriMesh decorated_tetrahedron() {
  TriMesh m = tetrahedron();
  m.positions[0].x = 0.1 + 1e-12;
  m.positions[3].z = -1.0 / 3.0;
  AttributeChannel& n = m.add_channel("normal", AttributeKind::kNormal, Storage::kPerVertex, 3);
  for (std::size_t v = 0; v < 4; ++v) n.element(v)[v % 3] = 1.0;
  AttributeChannel& c = m.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3);
  for (std::size_t v = 0; v < 4; ++v) c.element(v)[0] = static_cast<double>(v * 51) / 255.0;
  AttributeChannel& q = m.add_channel("quality", AttributeKind::kScalar, Storage::kPerVertex, 1);
  for (std::size_t v = 0; v < 4; ++v) q.values[v] = 0.5 * static_cast<double>(v);
  AttributeChannel& uv =
      m.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerVertex, 2);
  for (std::size_t v = 0; v < 4; ++v) uv.element(v)[1] = 0.25 * static_cast<double>(v);
  return m;
}

void expect_same(const TriMesh& a, const TriMesh& b, double tolerance) {
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.faces, b.faces);
  for (std::size_t v = 0; v < a.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a.positions[v][k], b.positions[v][k], tolerance);
  for (const AttributeChannel& c : a.channels) {
    const AttributeChannel* d = b.channel(c.name);
    ASSERT_NE(d, nullptr) << c.name;
    EXPECT_EQ(d->storage, c.storage) << c.name;
    EXPECT_EQ(d->kind, c.kind) << c.name;
    ASSERT_EQ(d->values.size(), c.values.size()) << c.name;
    for (std::size_t i = 0; i < c.values.size(); ++i)
      EXPECT_NEAR(d->values[i], c.values[i],
                  c.kind == AttributeKind::kColor ? 0.5 / 255 : tolerance)
          << c.name;
  }
}

TEST(WritePly, BinaryAndAsciiRoundTripExactly) {
  std::string dir = scratch_dir("write_ply_rt");
  TriMesh m = decorated_tetrahedron();
  for (bool binary : {true, false}) {
    std::string path = dir + (binary ? "/b.ply" : "/a.ply");
    PlyWriteOptions options;
    options.binary = binary;
    options.double_attributes = true;
    PlyWriteResult r = write_ply(path, m, options);
    EXPECT_TRUE(r.skipped_channels.empty());
    TriMesh back = read_mesh(path);
    expect_same(m, back, 0.0);
    EXPECT_EQ(back.positions[0].x, 0.1 + 1e-12);
  }
}

TEST(WritePly, FloatOptionLosesOnlyFloatPrecision) {
  std::string path = scratch_dir("write_ply_float") + "/f.ply";
  PlyWriteOptions options;
  options.double_positions = false;
  write_ply(path, decorated_tetrahedron(), options);
  expect_same(decorated_tetrahedron(), read_mesh(path), 1e-7);
}

TEST(WritePly, CornerUVsFaceChannelsAndTextureComment) {
  std::string dir = scratch_dir("write_ply_corner");
  TriMesh m = grid(2);
  AttributeChannel& uv =
      m.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerCorner, 2);
  for (std::size_t i = 0; i < uv.values.size(); ++i) uv.values[i] = static_cast<double>(i) / 64.0;
  AttributeChannel& fc = m.add_channel("color", AttributeKind::kColor, Storage::kPerFace, 3);
  fc.values.assign(fc.values.size(), 1.0);
  AttributeChannel& label = m.add_channel("label", AttributeKind::kScalar, Storage::kPerFace, 1);
  for (std::size_t f = 0; f < label.values.size(); ++f) label.values[f] = static_cast<double>(f);
  m.add_channel("hard_normal", AttributeKind::kNormal, Storage::kPerCorner, 3);
  m.texture_file = dir + "/tex.png";
  PlyWriteResult r = write_ply(dir + "/c.ply", m);
  ASSERT_EQ(r.skipped_channels, std::vector<std::string>{"hard_normal"});
  TriMesh back = read_mesh(dir + "/c.ply");
  EXPECT_EQ(back.texture_file, dir + "/tex.png");
  m.channels.pop_back();  // the skipped one
  expect_same(m, back, 1e-7);
}

TEST(WritePly, RealBunnyRoundTrip) {
  std::string data = shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "shared data folder (../shared/data) not present";
  TriMesh m = read_mesh(data + "/scalar/stanford_bunny/bun_zipper.ply");
  std::string path = scratch_dir("write_ply_bunny") + "/bunny.ply";
  PlyWriteOptions options;
  options.double_attributes = true;  // the ascii values were parsed into double
  write_ply(path, m, options);
  expect_same(m, read_mesh(path), 0.0);
}

TEST(WriteObj, RoundTripWithPerVertexAndPerCornerAttributes) {
  std::string dir = scratch_dir("write_obj_rt");
  TriMesh m = decorated_tetrahedron();
  m.channels.erase(m.channels.begin() + 2);  // quality: not representable in OBJ
  write_obj(dir + "/v.obj", m, {"v.mtl", "skin"});
  expect_same(m, read_mesh(dir + "/v.obj"), 0.0);

  TriMesh g = grid(3);
  AttributeChannel& uv =
      g.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerCorner, 2);
  for (std::size_t i = 0; i < uv.values.size(); ++i)
    uv.values[i] = static_cast<double>(i % 7) / 7.0;
  write_obj(dir + "/c.obj", g);
  TriMesh back = read_mesh(dir + "/c.obj");
  EXPECT_EQ(back.channel("texcoord")->storage, Storage::kPerCorner);
  expect_same(g, back, 0.0);
}

}  // namespace
}  // namespace meshdev::test
