// The results CSV: numbers, quoting, torn lines, incomplete jobs.
#include "harness/results_csv.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "metric/errors.h"

namespace meshdev::harness {
namespace {

ResultRow row(const std::string& key, int index, int count, const std::string& measure) {
  ResultRow r;
  r.set("job_key", key);
  r.set("mesh", "m.ply");
  r.set("simplifier", "s");
  r.set("reduction_percent", "90");
  r.set("status", "ok");
  r.set("measure", measure);
  r.set_count("measure_index", static_cast<std::size_t>(index));
  r.set_count("measure_count", static_cast<std::size_t>(count));
  return r;
}

TEST(ResultsCsv, NumbersRoundTripAndNanIsEmpty) {
  const double v = 0.1 + 0.2;
  EXPECT_EQ(std::stod(format_number(v)), v);
  EXPECT_EQ(format_number(std::nan("")), "");
  EXPECT_EQ(format_number(std::numeric_limits<double>::infinity()), "");
  ResultRow r;
  r.set_number("hausdorff", std::nan(""));
  EXPECT_EQ(r.get("hausdorff"), "");
  EXPECT_TRUE(std::isnan(r.number("hausdorff")));
  r.set_number("hausdorff", 1e-300);
  EXPECT_EQ(r.number("hausdorff"), 1e-300);
}

TEST(ResultsCsv, QuotingFollowsRfc4180) {
  ResultRow r = row("k", 0, 1, "geometry");
  r.set("message", "said \"no\", twice\nthen stopped");
  r.set("options", "a=1;b=2");
  const std::string text = format_header() + format_row(r);
  const ParsedResults p = parse_results(text, "t.csv");
  ASSERT_EQ(p.rows.size(), 1u);
  EXPECT_EQ(p.rows[0].get("message"), "said \"no\", twice then stopped");  // no line break
  EXPECT_EQ(p.rows[0].get("options"), "a=1;b=2");
  std::vector<std::string> f;
  EXPECT_TRUE(parse_csv_record("a,\"b,c\",\"d\"\"e\"", f));
  EXPECT_EQ(f, (std::vector<std::string>{"a", "b,c", "d\"e"}));
  EXPECT_FALSE(parse_csv_record("a,\"unterminated", f));
}

TEST(ResultsCsv, TornLastLineAndBadLinesAreDropped) {
  const std::string full = format_header() + format_row(row("k1", 0, 1, "geometry")) +
                           format_row(row("k2", 0, 1, "geometry"));
  const std::string torn = full.substr(0, full.size() - 7);
  const ParsedResults p = parse_results(torn, "t.csv");
  EXPECT_EQ(p.rows.size(), 1u);
  EXPECT_EQ(p.dropped_lines, 1u);
  const ParsedResults q = parse_results(format_header() + "a,b,c\n", "t.csv");
  EXPECT_EQ(q.rows.size(), 0u);
  EXPECT_EQ(q.dropped_lines, 1u);
  // A torn header (killed while writing it) is an empty file, not an error.
  EXPECT_EQ(parse_results(format_header().substr(0, 20), "t.csv").rows.size(), 0u);
}

TEST(ResultsCsv, ForeignHeaderIsRefused) {
  EXPECT_THROW(parse_results("a,b,c\n1,2,3\n", "t.csv"), ParseError);
}

TEST(ResultsCsv, IncompleteJobsAreDroppedAndRepeatsKeptOnce) {
  std::vector<ResultRow> rows = {row("a", 0, 2, "geometry"), row("a", 1, 2, "normal"),
                                 row("b", 0, 2, "geometry"), row("c", 0, 1, ""),
                                 row("c", 0, 1, "")};
  std::vector<std::string> warnings;
  const std::vector<ResultRow> kept = keep_complete_jobs(rows, warnings);
  ASSERT_EQ(kept.size(), 3u);
  EXPECT_EQ(kept[0].get("job_key"), "a");
  EXPECT_EQ(kept[2].get("job_key"), "c");
  EXPECT_EQ(warnings.size(), 2u);
}

TEST(ResultsCsv, SameExceptTimingIgnoresOnlyTimes) {
  ResultRow a = row("a", 0, 1, "geometry"), b = a;
  b.set_number("simplify_seconds", 3.0);
  b.set_number("metric_seconds", 4.0);
  EXPECT_TRUE(same_except_timing(a, b));
  b.set_number("symmetric_mean", 1.0);
  EXPECT_FALSE(same_except_timing(a, b));
}

}  // namespace
}  // namespace meshdev::harness
