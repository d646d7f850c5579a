// A decimation library's test, written against the installed meshdev package.
#include <gtest/gtest.h>

#include "harness/testing/deviation_assertions.h"
#include "metric/mesh.h"

namespace {

// A unit square (two triangles) and a copy lifted by 0.01.
meshdev::TriMesh square(double z) {
  meshdev::TriMesh m;
  m.positions = {{0, 0, z}, {1, 0, z}, {1, 1, z}, {0, 1, z}};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TEST(Consumer, DeviationWithinBound) {
  EXPECT_SYMMETRIC_DEVIATION_AT_MOST(square(0), square(0), 0.0);
  EXPECT_SYMMETRIC_DEVIATION_AT_MOST(square(0), square(0.01), 0.011);
}

TEST(Consumer, DeviationAboveBoundFails) {
  EXPECT_FALSE(meshdev::testing::symmetric_deviation_at_most("a", "b", "m", "bound", square(0),
                                                             square(0.01), "geometry", 0.001));
}

}  // namespace
