// A small sweep end to end on meshes built in code: rows, failed simplifiers as status rows,
// resume after a torn write, shards + merge equal to one run, the lock, --jobs.
#include "harness/sweep.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "harness/results_csv.h"
#include "harness/shard.h"
#include "metric/compare.h"
#include "metric/errors.h"
#include "metric/io/mesh_io.h"
#include "metric/io/write_ply.h"
#include "simplifiers/registry.h"
#include "tests/support/shapes.h"
#include "tests/support/test_data.h"

namespace meshdev::harness {
namespace {

// A backend that always reports failure, and one that throws.
class FailingSimplifier : public Simplifier {
 public:
  std::string name() const override { return "fake-fails"; }
  std::string description() const override { return "always fails"; }
  std::string role() const override { return "test"; }
  std::string keeps() const override { return "nothing"; }
  SimplifyResult simplify(const TriMesh& mesh, const SimplifyRequest& request) override {
    SimplifyResult r;
    r.input_faces = mesh.num_faces();
    r.target_faces = resolve_target_faces(request, mesh.num_faces());
    r.status = SimplifyStatus::kFailed;
    r.message = "refused on purpose";
    return r;
  }
};
class ThrowingSimplifier : public FailingSimplifier {
 public:
  std::string name() const override { return "fake-throws"; }
  SimplifyResult simplify(const TriMesh&, const SimplifyRequest&) override {
    throw std::runtime_error("crashed on purpose");
  }
};

std::unique_ptr<Simplifier> factory(const std::string& name) {
  if (name == "fake-fails") return std::make_unique<FailingSimplifier>();
  if (name == "fake-throws") return std::make_unique<ThrowingSimplifier>();
  return create_simplifier(name);
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class SweepTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    write_ply(dir_ + "/sphere.ply", test::icosphere(3));
    write_ply(dir_ + "/grid.ply", test::grid(10));
    config_ = parse_sweep_config(R"({"meshes": ["sphere.ply", "grid.ply"],
        "simplifiers": ["openmesh-quadric", "fake-fails", "fake-throws"],
        "ratios": [50, 90], "sample_count": 3000, "plots": false})",
                                 dir_, "test.json");
    if (create_simplifier("meshopt")->available()) config_.simplifiers.push_back({"meshopt", {}});
  }
  SweepSummary run(const std::string& out, ShardSpec shard = {}, int jobs = 1) {
    SweepOptions o;
    o.output_dir = dir_ + "/" + out;
    o.shard = shard;
    o.factory = factory;
    config_.jobs = jobs;
    return run_sweep(config_, o);
  }
  std::vector<ResultRow> rows(const std::string& out) {
    return read_results_file(dir_ + "/" + out + "/sweep.csv").rows;
  }
  static void expect_same(const std::vector<ResultRow>& a, const std::vector<ResultRow>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
      EXPECT_TRUE(same_except_timing(a[i], b[i]))
          << "row " << i << ": " << format_row(a[i]) << "vs\n"
          << format_row(b[i]);
  }
  std::string dir_;
  SweepConfig config_;
};

TEST_F(SweepTest, EveryJobGivesRowsAndFailuresAreStatusRows) {
  const SweepSummary s = run("out");
  const std::size_t sims = config_.simplifiers.size();
  EXPECT_EQ(s.jobs_total, 2 * sims * 2);
  EXPECT_EQ(s.jobs_run, s.jobs_total);
  EXPECT_EQ(s.jobs_failed, 2u * 2 * 2);  // two fake backends x 2 meshes x 2 ratios
  EXPECT_TRUE(s.complete);
  const std::vector<ResultRow> r = rows("out");
  std::size_t ok = 0, failed = 0;
  for (const ResultRow& row : r) {
    if (row.get("status") == "failed") {
      ++failed;
      EXPECT_EQ(row.get("measure"), "");
      EXPECT_TRUE(row.get("message") == "refused on purpose" ||
                  row.get("message") == "crashed on purpose")
          << row.get("message");
      continue;
    }
    ASSERT_TRUE(row.get("status") == "ok" || row.get("status") == "target-not-reached");
    ++ok;
    // The symmetric average is the mean of the two directions (paper §3.3).
    EXPECT_DOUBLE_EQ(row.number("symmetric_mean"),
                     0.5 * (row.number("forward_mean") + row.number("backward_mean")));
    EXPECT_GE(row.number("hausdorff"), row.number("forward_max"));
    if (row.get("measure") == "geometry") {
      EXPECT_DOUBLE_EQ(row.number("symmetric_mean_rel"),
                       row.number("symmetric_mean") / row.number("diagonal"));
      EXPECT_GT(row.number("symmetric_mean"), 0.0);
    } else {
      EXPECT_EQ(row.get("symmetric_mean_rel"), "");  // relative only for geometry
    }
  }
  EXPECT_EQ(failed, 8u);
  EXPECT_GT(ok, 0u);
  // Deviation grows with the reduction on the sphere (90 % is coarser than 50 %).
  double m50 = 0, m90 = 0;
  for (const ResultRow& row : r)
    if (row.get("mesh") == "sphere.ply" && row.get("simplifier") == "openmesh-quadric" &&
        row.get("measure") == "geometry")
      (row.number("reduction_percent") == 50 ? m50 : m90) = row.number("symmetric_mean");
  EXPECT_LT(m50, m90);
  EXPECT_TRUE(std::filesystem::exists(dir_ + "/out/sweep.json"));
}

TEST_F(SweepTest, ResumeAfterTornWriteComputesOnlyMissingRows) {
  run("full");
  const std::vector<ResultRow> full = rows("full");
  // Simulate a crash: keep the first 60 % of the bytes (the last line is torn).
  std::filesystem::create_directories(dir_ + "/part");
  const std::string text = read_text(dir_ + "/full/sweep.csv");
  {
    std::ofstream out(dir_ + "/part/sweep.csv", std::ios::binary);
    out << text.substr(0, text.size() * 6 / 10);
  }
  const SweepSummary s = run("part");
  EXPECT_GT(s.jobs_present, 0u);
  EXPECT_LT(s.jobs_run, s.jobs_total);
  EXPECT_EQ(s.jobs_present + s.jobs_run, s.jobs_total);
  EXPECT_GT(s.rows_dropped, 0u);
  expect_same(full, rows("part"));
  // A complete sweep run again computes nothing and leaves the file byte-identical.
  const std::string before = read_text(dir_ + "/part/sweep.csv");
  EXPECT_EQ(run("part").jobs_run, 0u);
  EXPECT_EQ(read_text(dir_ + "/part/sweep.csv"), before);
}

TEST_F(SweepTest, ChangedParametersAreRecomputedAndStaleRowsMovedAside) {
  run("out");
  config_.seed = 2;  // part of every job key
  const SweepSummary s = run("out");
  EXPECT_EQ(s.jobs_run, s.jobs_total);
  EXPECT_TRUE(std::filesystem::exists(dir_ + "/out/sweep.csv.stale"));
  for (const ResultRow& r : rows("out")) EXPECT_EQ(r.get("seed"), "2");
}

TEST_F(SweepTest, ShardsPlusMergeEqualTheSingleRun) {
  run("single");
  std::vector<std::string> parts;
  std::size_t jobs = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string out = "shard" + std::to_string(i);
    const SweepSummary s = run(out, ShardSpec{i, 3});
    jobs += s.jobs_in_shard;
    parts.push_back(dir_ + "/" + out + "/sweep.csv");
  }
  const MergeResult m = merge_results(parts);
  EXPECT_EQ(jobs, m.jobs);
  expect_same(rows("single"), m.rows);
  // The same shard twice is kept once.
  parts.push_back(parts.front());
  EXPECT_EQ(merge_results(parts).rows.size(), m.rows.size());
  EXPECT_THROW(parse_shard("3/3"), InvalidInput);
  EXPECT_THROW(parse_shard("x"), InvalidInput);
}

TEST_F(SweepTest, JobsInParallelGiveTheSameRows) {
  run("one", {}, 1);
  run("two", {}, 2);
  expect_same(rows("one"), rows("two"));
}

// Each row holds what a fresh comparison of the mesh with that simplification gives, bit for bit
// (the sweep compares a group's simplifications with one ComparisonReference of the mesh).
TEST_F(SweepTest, RowsEqualAFreshComparisonOfEachSimplification) {
  config_.meshes = {"sphere.ply"};
  config_.simplifiers = {{"openmesh-quadric", {}}};
  config_.reduction_percent = {50, 75, 90};
  run("out");
  const std::vector<ResultRow> r = rows("out");
  const TriMesh sphere = read_mesh(dir_ + "/sphere.ply");
  std::vector<SimplifyRequest> requests;
  for (double ratio : config_.reduction_percent)
    requests.push_back(SimplifyRequest::reduction(ratio / 100));
  const std::vector<SimplifyResult> simplified =
      create_simplifier("openmesh-quadric")->simplify_sweep(sphere, requests);
  ASSERT_EQ(simplified.size(), requests.size());
  std::size_t checked = 0;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const ComparisonResult fresh =
        compare_meshes(sphere, simplified[i].mesh, compare_options(config_));
    for (std::size_t m = 0; m < fresh.measures.size(); ++m)
      for (const ResultRow& row : r) {
        if (row.number("reduction_percent") != config_.reduction_percent[i] ||
            row.get("measure") != fresh.measures[m].name)
          continue;
        EXPECT_EQ(row.number("forward_mean"), fresh.forward->stats[m].mean);
        EXPECT_EQ(row.number("forward_p95"), fresh.forward->stats[m].p95);
        EXPECT_EQ(row.number("backward_rms"), fresh.backward->stats[m].rms);
        EXPECT_EQ(row.number("backward_max"), fresh.backward->stats[m].max);
        EXPECT_EQ(row.number("symmetric_mean"), fresh.symmetric[m].mean);
        EXPECT_EQ(row.number("hausdorff"), fresh.symmetric[m].hausdorff);
        ++checked;
      }
  }
  EXPECT_EQ(checked, r.size());
  EXPECT_GE(checked, 3u * 2);  // geometry and normals at least, for each ratio
}

TEST_F(SweepTest, ASecondSweepOnTheSameCsvIsRefused) {
  std::filesystem::create_directories(dir_ + "/out");
  const int fd = ::open((dir_ + "/out/sweep.csv.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  EXPECT_THROW(run("out"), WriteError);
  ::close(fd);
}

TEST_F(SweepTest, UnknownSimplifierOrOptionFailsBeforeAnyWork) {
  config_.simplifiers = {{"no-such-backend", {}}};
  EXPECT_THROW(run("bad"), InvalidInput);
  config_.simplifiers = {{"openmesh-quadric", {{"no_such_option", "1"}}}};
  EXPECT_THROW(run("bad"), InvalidInput);
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/bad/sweep.csv"));
}

TEST(JobKeys, DependOnContentsOptionsRatioAndSampling) {
  SweepConfig c;
  c.meshes = {"a.ply"};
  const std::vector<SimplifierSpec> s = {{"x", {}}, {"x", {{"k", "1"}}}};
  const std::vector<Job> j = make_jobs(c, s, {"h1"});
  ASSERT_EQ(j.size(), 12u);
  std::set<std::string> keys;
  for (const Job& job : j) keys.insert(job.key);
  EXPECT_EQ(keys.size(), 12u);
  EXPECT_NE(make_jobs(c, s, {"h2"})[0].key, j[0].key);
  c.sample_count = 5;
  EXPECT_NE(make_jobs(c, s, {"h1"})[0].key, j[0].key);
  c.sample_count = 0;
  EXPECT_EQ(make_jobs(c, s, {"h1"})[0].key, j[0].key);
}

}  // namespace
}  // namespace meshdev::harness
