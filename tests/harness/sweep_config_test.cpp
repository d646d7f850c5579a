// Sweep configs: a one-line config works with defaults; errors name the key.
#include "harness/sweep_config.h"

#include <gtest/gtest.h>

#include "metric/errors.h"

namespace meshdev::harness {
namespace {

TEST(SweepConfig, OneLineConfigGetsDefaults) {
  const SweepConfig c = parse_sweep_config(R"({"meshes": ["bunny00.off"]})", "cfg", "c.json");
  ASSERT_EQ(c.meshes.size(), 1u);
  EXPECT_EQ(c.meshes[0], "bunny00.off");
  EXPECT_EQ(resolve_mesh_path(c, 0), "cfg/bunny00.off");
  EXPECT_TRUE(c.simplifiers.empty());  // every available backend
  EXPECT_EQ(c.reduction_percent, (std::vector<double>{50, 75, 90, 95, 98, 99}));
  EXPECT_EQ(c.sampling, "vertices,faces");
  EXPECT_TRUE(c.attributes.empty());
  EXPECT_EQ(c.seed, 1u);
  const CompareOptions o = compare_options(c);
  EXPECT_TRUE(o.sampling.vertices);
  EXPECT_EQ(o.sampling.faces, FaceSampling::kScanConversion);
}

TEST(SweepConfig, SimplifiersWithOptionsRatiosAndSampling) {
  const SweepConfig c = parse_sweep_config(R"({
      "meshes": ["/abs/a.ply"],
      "simplifiers": ["cgal-gh", {"name": "openmesh-hausdorff", "options": {"tolerance": "1%"}},
                      "meshopt:target_error=0.5"],
      "ratios": [50, "90%"], "sampling": "montecarlo", "sample_count": 1000, "seed": 7,
      "step": "0.5%", "attributes": ["geometry", "normal"]})",
                                           "cfg", "c.json");
  EXPECT_EQ(resolve_mesh_path(c, 0), "/abs/a.ply");
  ASSERT_EQ(c.simplifiers.size(), 3u);
  EXPECT_EQ(c.simplifiers[1].options_text(), "tolerance=1%");
  EXPECT_EQ(c.simplifiers[2].name, "meshopt");
  EXPECT_EQ(c.simplifiers[2].options_text(), "target_error=0.5");
  EXPECT_EQ(c.reduction_percent, (std::vector<double>{50, 90}));
  EXPECT_DOUBLE_EQ(c.step_fraction, 0.005);
  EXPECT_EQ(compare_options(c).sampling.faces, FaceSampling::kMonteCarlo);
  // The resolved config round-trips through its JSON.
  const SweepConfig d = parse_sweep_config(config_to_json(c), "cfg", "d.json");
  EXPECT_EQ(sampling_text(c), sampling_text(d));
  EXPECT_EQ(d.simplifiers[1].options_text(), "tolerance=1%");
}

TEST(SweepConfig, MistakesAreNamed) {
  auto msg = [](const std::string& json) {
    try {
      parse_sweep_config(json, "", "c.json");
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(msg(R"({"mesh": ["a"]})").find("unknown key 'mesh'"), std::string::npos);
  EXPECT_NE(msg(R"({"ratios": [50]})").find("meshes"), std::string::npos);
  EXPECT_NE(msg(R"({"meshes": ["a"], "ratios": [100]})").find("(0, 100)"), std::string::npos);
  EXPECT_NE(msg(R"({"meshes": ["a"], "sampling": "corners"})").find("corners"), std::string::npos);
  EXPECT_NE(msg(R"({"meshes": ["a"], "jobs": 0})").find("jobs"), std::string::npos);
  EXPECT_NE(msg(R"({"meshes": ["a"], "threads": -1})").find("threads"), std::string::npos);
  EXPECT_NE(msg(R"({"meshes": ["a"], "threads": 100000})").find("threads"), std::string::npos);
  // Refused here, before any mesh is read, not as a metric-failed row per job.
  EXPECT_NE(msg(R"({"meshes": ["a"], "sample_count": 4000000000})").find("more than the 2^31"),
            std::string::npos);
  EXPECT_THROW(parse_sweep_config("{not json", "", "c.json"), ParseError);
}

}  // namespace
}  // namespace meshdev::harness
