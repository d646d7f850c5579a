#include "metric/mesh.h"

#include <gtest/gtest.h>

#include <limits>

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

}  // namespace
}  // namespace meshdev
