// The regression guard: identical passes; worse, missing and failed rows regress.
#include "harness/guard.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "metric/errors.h"

namespace meshdev::harness {
namespace {

ResultRow row(const std::string& simplifier, double ratio, const std::string& measure, double mean,
              double hausdorff) {
  ResultRow r;
  r.set("job_key", simplifier + std::to_string(ratio));
  r.set("mesh", "bunny.off");
  r.set("simplifier", simplifier);
  r.set_number("reduction_percent", ratio);
  r.set("status", "ok");
  r.set("measure", measure);
  r.set_number("symmetric_mean", mean);
  r.set_number("hausdorff", hausdorff);
  r.set("tool_version", "0.1.0");
  return r;
}

std::vector<ResultRow> baseline() {
  return {row("cgal-gh", 50, "geometry", 1e-4, 1e-3), row("cgal-gh", 50, "normal", 0.02, 0.5),
          row("cgal-gh", 90, "geometry", 3e-4, 4e-3), row("meshopt", 90, "geometry", 0, 0)};
}

TEST(Guard, IdenticalResultsPass) {
  const GuardResult r = run_guard(baseline(), baseline(), GuardOptions{});
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(r.rows_compared, 4u);
  EXPECT_EQ(r.values_compared, 8u);
  EXPECT_NE(format_guard_report(r, GuardOptions{}).find("PASS"), std::string::npos);
}

TEST(Guard, WithinToleranceAndADifferentToolVersionPass) {
  std::vector<ResultRow> cur = baseline();
  cur[0].set_number("symmetric_mean", 1.04e-4);  // +4 % < 5 %
  cur[3].set_number("hausdorff", 1e-13);         // 0 -> 1e-13: inside the absolute tolerance
  for (ResultRow& r : cur) r.set("tool_version", "0.2.0");
  EXPECT_TRUE(run_guard(baseline(), cur, GuardOptions{}).passed());
}

TEST(Guard, DegradedValueFailsWithATable) {
  std::vector<ResultRow> cur = baseline();
  cur[2].set_number("symmetric_mean", 3.6e-4);  // +20 %
  const GuardResult r = run_guard(baseline(), cur, GuardOptions{});
  ASSERT_EQ(r.regressions.size(), 1u);
  EXPECT_EQ(r.regressions[0].verdict, "worse");
  EXPECT_EQ(r.regressions[0].metric, "symmetric_mean");
  EXPECT_NEAR(r.regressions[0].change, 0.2, 1e-9);
  const std::string table = format_guard_report(r, GuardOptions{});
  EXPECT_NE(table.find("FAIL"), std::string::npos);
  EXPECT_NE(table.find("+20.0%"), std::string::npos);
  // Better is never a regression; a looser tolerance lets it pass.
  GuardOptions loose;
  loose.tolerance = 0.25;
  EXPECT_TRUE(run_guard(baseline(), cur, loose).passed());
}

TEST(Guard, MissingRowAndFailedStatusAreRegressions) {
  std::vector<ResultRow> cur = baseline();
  cur.erase(cur.begin() + 1);  // the normal row is gone
  GuardResult r = run_guard(baseline(), cur, GuardOptions{});
  ASSERT_EQ(r.regressions.size(), 1u);
  EXPECT_EQ(r.regressions[0].verdict, "missing");

  cur = baseline();
  ResultRow failed = row("meshopt", 90, "", 0, 0);
  failed.set("status", "failed");
  failed.set("message", "refused the input");
  failed.set("symmetric_mean", "");
  failed.set("hausdorff", "");
  cur[3] = failed;
  r = run_guard(baseline(), cur, GuardOptions{});
  ASSERT_EQ(r.regressions.size(), 1u);
  EXPECT_EQ(r.regressions[0].verdict, "failed");
  EXPECT_NE(r.regressions[0].current.find("refused the input"), std::string::npos);
}

TEST(Guard, MetricsAndMeasuresSelectWhatIsChecked) {
  std::vector<ResultRow> cur = baseline();
  cur[1].set_number("hausdorff", 0.9);  // normal Hausdorff much worse
  GuardOptions o;
  o.metrics = {"symmetric_mean"};
  EXPECT_TRUE(run_guard(baseline(), cur, o).passed());
  o.metrics = {"hausdorff"};
  o.measures = {"geometry"};
  EXPECT_TRUE(run_guard(baseline(), cur, o).passed());
  o.measures = {};
  EXPECT_FALSE(run_guard(baseline(), cur, o).passed());
  o.metrics = {"mesh"};
  EXPECT_THROW(run_guard(baseline(), cur, o), InvalidInput);
}

// What would compare nothing, or let anything pass, is an error, not a PASS: an empty baseline
// (a PASS of 0 values before), a measure no baseline row has (a typo passed every run), a NaN or
// negative tolerance (`--absolute-tolerance nan` passed every run).
TEST(Guard, WhatWouldLetEveryRunPassIsRejected) {
  EXPECT_THROW(run_guard({}, baseline(), GuardOptions{}), InvalidInput);
  GuardOptions o;
  o.measures = {"geomtry"};
  EXPECT_THROW(run_guard(baseline(), baseline(), o), InvalidInput);
  o.measures = {"normal"};
  EXPECT_TRUE(run_guard(baseline(), baseline(), o).passed());
  for (double bad : {std::nan(""), -1e-12, std::numeric_limits<double>::infinity()}) {
    GuardOptions absolute, relative;
    absolute.absolute_tolerance = bad;
    relative.tolerance = bad;
    EXPECT_THROW(run_guard(baseline(), baseline(), absolute), InvalidInput) << bad;
    EXPECT_THROW(run_guard(baseline(), baseline(), relative), InvalidInput) << bad;
  }
}

TEST(Guard, ToleranceParsing) {
  EXPECT_DOUBLE_EQ(parse_tolerance("5%"), 0.05);
  EXPECT_DOUBLE_EQ(parse_tolerance("0.1"), 0.1);
  EXPECT_THROW(parse_tolerance("-1%"), InvalidInput);
  EXPECT_THROW(parse_tolerance("five"), InvalidInput);
}

}  // namespace
}  // namespace meshdev::harness
