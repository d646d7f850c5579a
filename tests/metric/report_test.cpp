#include "metric/report.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "metric/errors.h"
#include "tests/support/shapes.h"

namespace meshdev {
namespace {

ComparisonResult offset_planes(bool keep) {
  CompareOptions o;
  o.keep_samples = keep;
  return compare_meshes(test::grid(4), test::grid(3, 1.0, 0.125), o, "a.off", "b.off");
}

TEST(Report, JsonCarriesSchemaStatisticsRelativeValuesAndSymmetry) {
  const nlohmann::json j = nlohmann::json::parse(to_json(offset_planes(false)));
  EXPECT_EQ(j["schema"], kCompareSchema);
  EXPECT_EQ(j["meshes"]["a"]["file"], "a.off");
  const auto& g = j["directions"]["forward"]["stats"]["geometry"];
  EXPECT_DOUBLE_EQ(g["max"].get<double>(), 0.125);
  EXPECT_DOUBLE_EQ(g["relative"]["max"].get<double>(), 0.125 / std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(j["symmetric"]["geometry"]["hausdorff"].get<double>(), 0.125);
  EXPECT_TRUE(j["directions"]["backward"]["stats"].contains("normal_angle"));
  EXPECT_EQ(j["options"]["sampling"]["faces"], "scan-conversion");
}

TEST(Report, SummaryCsvHasOneRowPerDirectionAndMeasure) {
  const ComparisonResult r = offset_planes(false);
  std::istringstream csv(to_summary_csv(r));
  std::string line;
  int rows = -1;  // header
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 3 * static_cast<int>(r.measures.size()));
}

TEST(Report, SamplesCsvHasOneRowPerSampleAndRoundTripsNumbers) {
  const ComparisonResult r = offset_planes(true);
  std::ostringstream out;
  write_samples_csv(out, r);
  std::istringstream in(out.str());
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("direction,sample,kind,", 0), 0u);
  std::size_t rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, r.forward->samples + r.backward->samples);
  EXPECT_THROW(write_samples_csv(out, offset_planes(false)), InvalidInput);
}

TEST(Report, TextReportShowsTheTableOneRows) {
  const std::string text = format_report(offset_planes(false));
  for (const char* word : {"vertices", "faces", "area", "geometry", "symmetric", "hausdorff"})
    EXPECT_NE(text.find(word), std::string::npos) << word;
}

}  // namespace
}  // namespace meshdev
