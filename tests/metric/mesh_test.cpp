#include "metric/mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>

#include "metric/errors.h"

#include "tests/support/shapes.h"

namespace meshdev {
namespace {

void expect_same_box(const BoundingBox& a, const BoundingBox& b) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(a.min[k], b.min[k]) << "axis " << k;
    EXPECT_EQ(a.max[k], b.max[k]) << "axis " << k;
  }
}

// The parallel box of the faces' corners is bounding_box(mesh) (the serial twin, over the
// referenced vertices) on any team size: unreferenced vertices far outside are not in it, NaN
// corners are ignored, a mesh without faces is the box of its vertices.
TEST(Mesh, CornerBoundingBoxEqualsTheSerialBoxOnAnyTeam) {
  TriMesh soup = test::random_soup(2000, 5);
  soup.positions.push_back({1e9, -1e9, 3e9});  // referenced by no face
  soup.positions[soup.faces[7][1]].y = std::numeric_limits<double>::quiet_NaN();
  TriMesh cloud;
  cloud.positions = {{1, 2, 3}, {-4, 5, 0.5}, {0, 0, -7}};
  for (const TriMesh* m : {&soup, &cloud})
    for (int threads : {1, 2, 3, 7}) {
      SCOPED_TRACE(threads);
      expect_same_box(corner_bounding_box(*m, threads), bounding_box(*m));
    }
  EXPECT_LT(corner_bounding_box(soup, 2).max.x, 1e9);
}

// The parallel box of all positions is the serial loop's on any team size: unreferenced
// vertices are in it, NaN coordinates are not.
TEST(Mesh, PositionBoundingBoxEqualsTheSerialLoopOnAnyTeam) {
  TriMesh soup = test::random_soup(2000, 6);
  soup.positions.push_back({1e9, -1e9, 3e9});  // referenced by no face
  soup.positions[soup.faces[7][1]].y = std::numeric_limits<double>::quiet_NaN();
  BoundingBox serial;
  for (const Vec3& p : soup.positions) serial.extend(p);
  EXPECT_EQ(serial.max.x, 1e9);
  for (int threads : {1, 2, 3, 7}) {
    SCOPED_TRACE(threads);
    expect_same_box(position_bounding_box(soup, threads), serial);
  }
}

// The team's surface area is the serial sum bit for bit (areas computed on the team, added in
// face order), on a soup large enough for the parallel path.
TEST(Mesh, SurfaceAreaOnATeamEqualsTheSerialSum) {
  const TriMesh soup = test::random_soup(20000, 7);
  const double serial = surface_area(soup);
  EXPECT_GT(serial, 0.0);
  for (int threads : {1, 2, 3, 7}) EXPECT_EQ(surface_area(soup, threads), serial) << threads;
}

// The referenced vertices' count and box are those of referenced_vertices and bounding_box on
// any team: an unreferenced vertex far outside counts for neither, a mesh without faces is boxed
// by all its vertices and references none.
TEST(Mesh, ReferencedVertexSummaryEqualsTheSerialTwinsOnAnyTeam) {
  TriMesh soup = test::random_soup(20000, 8);
  soup.positions.push_back({1e9, -1e9, 3e9});  // referenced by no face
  soup.faces[5] = {soup.faces[4][0], soup.faces[4][1],
                   soup.faces[4][2]};  // face 5's corners unused
  const std::vector<bool> used = referenced_vertices(soup);
  const auto count = static_cast<std::size_t>(std::count(used.begin(), used.end(), true));
  EXPECT_EQ(count, soup.positions.size() - 4);
  TriMesh cloud;
  cloud.positions = {{1, 2, 3}, {-4, 5, 0.5}, {0, 0, -7}};
  for (int threads : {1, 2, 3, 7}) {
    SCOPED_TRACE(threads);
    const ReferencedVertices r = referenced_vertex_summary(soup, threads);
    EXPECT_EQ(r.count, count);
    expect_same_box(r.box, bounding_box(soup));
    const ReferencedVertices c = referenced_vertex_summary(cloud, threads);
    EXPECT_EQ(c.count, 0u);
    expect_same_box(c.box, bounding_box(cloud));
  }
}

// validate names the lowest offending element whatever the team: a vertex, a face, a channel
// value (each with a later one also wrong).
TEST(Mesh, ValidateNamesTheFirstBadElementOnAnyTeam) {
  const TriMesh good = test::random_soup(20000, 9);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  TriMesh bad_vertex = good, bad_face = good, bad_channel = good;
  bad_vertex.positions[41000].z = nan;
  bad_vertex.positions[30001].x = std::numeric_limits<double>::infinity();
  bad_face.faces[19000][2] = 70000;
  bad_face.faces[17001][1] = 60001;
  AttributeChannel& t =
      bad_channel.add_channel("temperature", AttributeKind::kScalar, Storage::kPerVertex, 1);
  t.values[50000] = nan;
  t.values[20002] = nan;
  auto message = [](const TriMesh& m, int threads) {
    try {
      validate(m, "m.ply", threads);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  for (int threads : {1, 2, 3, 7}) {
    SCOPED_TRACE(threads);
    EXPECT_EQ(message(good, threads), "accepted");
    EXPECT_EQ(message(bad_vertex, threads), "m.ply: vertex 30001 has a non-finite coordinate");
    EXPECT_EQ(message(bad_face, threads),
              "m.ply: face 17001 uses vertex 60001 but the mesh has 60000 vertices");
    EXPECT_EQ(message(bad_channel, threads),
              "m.ply: attribute 'temperature' element 20002 is not finite");
  }
}

}  // namespace
}  // namespace meshdev
