#pragma once
// GoogleTest assertions for decimation code: "the simplified mesh stays within BOUND of the
// original", measured with the attribute deviation metric (symmetric average of the two
// directions' mean deviations, the paper's §3.3). Header-only; from another CMake project:
//
//   find_package(meshdev REQUIRED)
//   target_link_libraries(my_tests PRIVATE meshdev::testing GTest::gtest_main)
//
//   #include "harness/testing/deviation_assertions.h"
//   EXPECT_SYMMETRIC_DEVIATION_AT_MOST(original, simplified, 0.01);    // geometry, absolute
//   EXPECT_SYMMETRIC_ATTRIBUTE_DEVIATION_AT_MOST(original, simplified, "normal", 0.05);
//   ASSERT_SYMMETRIC_DEVIATION_AT_MOST(original, simplified, 0.01);
//
// Bounds are in the measure's absolute units (geometry: the meshes' length unit; normal: length
// of the difference of unit normals). Sampling is the metric's default (vertices + scan-converted
// faces, 10 x the larger face count per direction), so the result is deterministic. Cost: one
// compare_meshes call, O(samples x log F).
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "metric/compare.h"
#include "metric/errors.h"
#include "metric/mesh.h"

namespace meshdev::testing {

// The symmetric mean deviation of `measure` between a and b with the default options, plus a
// description for failure messages. Throws InvalidInput if the measure cannot be computed.
inline double symmetric_mean_deviation(const TriMesh& a, const TriMesh& b,
                                       const std::string& measure, std::string* description) {
  CompareOptions options;
  if (measure != "geometry") options.attributes.attributes = {"geometry", measure};
  const ComparisonResult r = compare_meshes(a, b, options, "a", "b");
  for (std::size_t m = 0; m < r.measures.size(); ++m) {
    if (r.measures[m].name != measure) continue;
    if (description) {
      std::ostringstream s;
      s.precision(6);
      s << "symmetric mean " << measure << " deviation " << r.symmetric[m].mean << " (forward "
        << r.forward->stats[m].mean << ", backward " << r.backward->stats[m].mean << ", Hausdorff "
        << r.symmetric[m].hausdorff << ", unit " << r.measures[m].unit << "; bbox diagonal of a "
        << r.diagonal << "; " << r.forward->samples << " + " << r.backward->samples << " samples)";
      *description = s.str();
    }
    return r.symmetric[m].mean;
  }
  throw InvalidInput("measure '" + measure + "' was not computed");
}

// Predicate-format function behind the macros (usable with EXPECT_PRED_FORMAT4 directly).
inline ::testing::AssertionResult symmetric_deviation_at_most(
    const char* a_expr, const char* b_expr, const char* measure_expr, const char* bound_expr,
    const TriMesh& a, const TriMesh& b, const std::string& measure, double bound) {
  std::string description;
  double value = 0;
  try {
    value = symmetric_mean_deviation(a, b, measure, &description);
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "cannot compare " << a_expr << " and " << b_expr << " ("
                                         << measure_expr << "): " << e.what();
  }
  if (value <= bound) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "between " << a_expr << " and " << b_expr << ": " << description
         << "\n  exceeds the bound " << bound_expr << " = " << bound;
}

}  // namespace meshdev::testing

#define EXPECT_SYMMETRIC_ATTRIBUTE_DEVIATION_AT_MOST(a, b, measure, bound) \
  EXPECT_PRED_FORMAT4(::meshdev::testing::symmetric_deviation_at_most, a, b, measure, bound)
#define ASSERT_SYMMETRIC_ATTRIBUTE_DEVIATION_AT_MOST(a, b, measure, bound) \
  ASSERT_PRED_FORMAT4(::meshdev::testing::symmetric_deviation_at_most, a, b, measure, bound)
#define EXPECT_SYMMETRIC_DEVIATION_AT_MOST(a, b, bound) \
  EXPECT_SYMMETRIC_ATTRIBUTE_DEVIATION_AT_MOST(a, b, std::string("geometry"), bound)
#define ASSERT_SYMMETRIC_DEVIATION_AT_MOST(a, b, bound) \
  ASSERT_SYMMETRIC_ATTRIBUTE_DEVIATION_AT_MOST(a, b, std::string("geometry"), bound)
