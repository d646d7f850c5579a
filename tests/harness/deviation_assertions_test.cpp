// The GoogleTest helper EXPECT_SYMMETRIC_DEVIATION_AT_MOST on meshes built in code.
#include "harness/testing/deviation_assertions.h"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include "tests/support/shapes.h"

namespace meshdev::testing {
namespace {

TEST(DeviationAssertions, IdenticalMeshesAreWithinZero) {
  const TriMesh s = test::icosphere(2);
  EXPECT_SYMMETRIC_DEVIATION_AT_MOST(s, s, 0.0);
  ASSERT_SYMMETRIC_DEVIATION_AT_MOST(s, s, 1e-12);
  EXPECT_SYMMETRIC_ATTRIBUTE_DEVIATION_AT_MOST(s, s, "normal", 0.0);
}

TEST(DeviationAssertions, AShiftedCopyIsWithinItsShiftButNotBelow) {
  const TriMesh a = test::grid(4);
  const TriMesh b = test::translated(a, {0, 0, 0.01});  // every point exactly 0.01 away
  EXPECT_SYMMETRIC_DEVIATION_AT_MOST(a, b, 0.0100001);
  EXPECT_NONFATAL_FAILURE(EXPECT_SYMMETRIC_DEVIATION_AT_MOST(a, b, 0.005),
                          "exceeds the bound 0.005");
  EXPECT_NONFATAL_FAILURE(
      EXPECT_SYMMETRIC_ATTRIBUTE_DEVIATION_AT_MOST(a, b, "no_such_channel", 1.0), "cannot compare");
}

}  // namespace
}  // namespace meshdev::testing
