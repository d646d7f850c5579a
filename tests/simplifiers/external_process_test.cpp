// Fault injection for external simplifiers: a fake program (fake_simplifier.sh) run through the
// `external` backend crashes, hangs, ignores SIGTERM, leaves a child behind, writes garbage /
// nothing / an empty file / NaN, floods its pipes, or works. Each gives the right status and
// message, returns within timeout + grace (+ slack for a loaded machine), and leaves no process
// of its group alive. Plus run_process itself, the command template and the PATH lookup.
#include <gtest/gtest.h>
#include <signal.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <ostream>

#include "metric/errors.h"
#include "simplifiers/external_process.h"
#include "simplifiers/external_simplifiers.h"
#include "simplifiers/registry.h"
#include "tests/simplifiers/fixtures.h"

#ifndef MESHDEV_FAKE_SIMPLIFIER
#error "MESHDEV_FAKE_SIMPLIFIER (path of fake_simplifier.sh) must be defined by the build"
#endif

namespace meshdev {
namespace {

constexpr double kTimeout = 1.5, kGrace = 0.5;
// Generous slack over timeout + grace: process start-up and teardown on a shared machine.
constexpr double kSlack = 3.0;

bool group_gone(pid_t pgid) {
  return pgid > 0 && kill(-pgid, 0) == -1 && errno == ESRCH;
}

struct Outcome {
  SimplifyResult result;
  ProcessResult process;
  double seconds = 0;
};

Outcome run_fake(const std::string& mode) {
  auto s = create_simplifier("external");
  s->set_option("command", std::string("/bin/bash ") + MESHDEV_FAKE_SIMPLIFIER + " " + mode +
                               " {input} {output} {faces}");
  s->set_option("output_format", "off");
  s->set_option("timeout", std::to_string(kTimeout));
  s->set_option("grace", std::to_string(kGrace));
  const auto start = std::chrono::steady_clock::now();
  Outcome o;
  o.result = s->simplify(test::fixture("icosphere4"), SimplifyRequest::reduction(0.9));
  o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  o.process = dynamic_cast<ExternalSimplifier&>(*s).last_process();
  return o;
}

struct Case {
  std::string mode;
  SimplifyStatus status;
  std::string message;  // a substring the message must contain
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.mode;
}

class FakeSimplifier : public ::testing::TestWithParam<Case> {};

TEST_P(FakeSimplifier, CleanStatusNothingLeftRunning) {
  const Case& c = GetParam();
  Outcome o = run_fake(c.mode);
  EXPECT_EQ(o.result.status, c.status)
      << c.mode << ": " << status_name(o.result.status) << ": " << o.result.message;
  EXPECT_NE(o.result.message.find(c.message), std::string::npos)
      << c.mode << ": message '" << o.result.message << "' lacks '" << c.message << "'";
  EXPECT_LT(o.seconds, kTimeout + kGrace + kSlack) << c.mode;
  ASSERT_TRUE(o.process.started) << o.process.error;
  EXPECT_TRUE(group_gone(o.process.pgid))
      << c.mode << ": process group " << o.process.pgid << " still has members";
  if (c.status == SimplifyStatus::kFailed) {
    EXPECT_EQ(o.result.mesh.num_faces(), 0u);
  } else {
    EXPECT_EQ(o.result.mesh.num_faces(), 4u);
    EXPECT_NO_THROW(validate(o.result.mesh, "fake output"));
  }
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  std::string s = info.param.mode;
  for (char& ch : s)
    if (!isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(
    Modes, FakeSimplifier,
    ::testing::Values(
        Case{"ok", SimplifyStatus::kOk, ""},
        Case{"fail", SimplifyStatus::kFailed, "exit code 3; stderr: fake: something went wrong"},
        Case{"crash", SimplifyStatus::kFailed, "killed by SIGSEGV; stderr: fake: about to crash"},
        Case{"hang", SimplifyStatus::kFailed, "timed out"},
        Case{"ignore-term", SimplifyStatus::kFailed, "SIGTERM ignored, SIGKILL"},
        Case{"fork", SimplifyStatus::kOk, "left running were terminated"},
        Case{"garbage", SimplifyStatus::kFailed, "output is not a valid mesh"},
        Case{"empty", SimplifyStatus::kFailed, "empty output file"},
        Case{"no-output", SimplifyStatus::kFailed, "wrote no output file"},
        Case{"flood", SimplifyStatus::kOk, ""},
        Case{"nan", SimplifyStatus::kFailed, "output is not a valid mesh"},
        Case{"no-such-mode", SimplifyStatus::kFailed, "exit code 2"}),
    case_name);

TEST(RunProcess, FloodIsCappedWithoutDeadlock) {
  ProcessOptions po;
  po.argv = {"/bin/bash", MESHDEV_FAKE_SIMPLIFIER, "flood", "/dev/null", "/dev/null", "1"};
  po.timeout_seconds = 60;
  po.capture_bytes = 64 * 1024;
  ProcessResult r = run_process(po);
  EXPECT_TRUE(r.ok()) << r.describe();
  EXPECT_GE(r.stderr_bytes, 20000000u);
  EXPECT_GE(r.stdout_bytes, 20000000u);
  EXPECT_LE(r.stderr_tail.size(), po.capture_bytes);
  EXPECT_LE(r.stdout_tail.size(), po.capture_bytes);
  EXPECT_NE(r.stderr_tail.find("fake: flood finished"), std::string::npos);  // the LAST bytes
  EXPECT_TRUE(group_gone(r.pgid));
}

TEST(RunProcess, StdinIsDevNullAndFolderIsUsed) {
  TempDir dir("meshdev-test-");
  ProcessOptions po;
  po.argv = {"/bin/sh", "-c", "cat; pwd; echo \"$MESHDEV_X\""};
  po.working_dir = dir.path();
  po.env = {{"MESHDEV_X", "hello"}};
  ProcessResult r = run_process(po);  // cat returns at once: stdin is /dev/null, not a TTY
  ASSERT_TRUE(r.ok()) << r.describe();
  EXPECT_NE(r.stdout_tail.find(std::filesystem::canonical(dir.path()).string()), std::string::npos);
  EXPECT_NE(r.stdout_tail.find("hello"), std::string::npos);
}

TEST(RunProcess, MissingProgramDoesNotStart) {
  ProcessOptions po;
  po.argv = {"meshdev-no-such-program-xyz"};
  ProcessResult r = run_process(po);
  EXPECT_FALSE(r.started);
  EXPECT_NE(r.describe().find("not found"), std::string::npos) << r.describe();
}

TEST(TempDir, IsRemovedWithItsContents) {
  std::string path;
  {
    TempDir dir;
    path = dir.path();
    ASSERT_TRUE(std::filesystem::is_directory(path));
    std::filesystem::create_directories(dir.file("a/b"));
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(ExternalCommand, MissingProgramIsUnavailableWithReason) {
  auto s = create_simplifier("external");
  EXPECT_FALSE(s->available());  // no command yet
  EXPECT_NE(s->unavailable_reason().find("no command"), std::string::npos);
  s->set_option("command", "meshdev-no-such-qslim -t {faces} -o {output} {input}");
  EXPECT_FALSE(s->available());
  EXPECT_NE(s->unavailable_reason().find("not found"), std::string::npos);
  SimplifyResult r = s->simplify(test::fixture("tetrahedron"), SimplifyRequest::faces(2));
  EXPECT_EQ(r.status, SimplifyStatus::kUnavailable);
  EXPECT_NE(r.message.find("meshdev-no-such-qslim"), std::string::npos) << r.message;
}

TEST(ExternalCommand, TemplateIsCheckedAndExpanded) {
  auto words = expand_command("q -t {faces} -o '{output} x' \"{input}\" r={ratio},k={keep}",
                              {{"input", "in.ply"},
                               {"output", "out.ply"},
                               {"faces", "10"},
                               {"ratio", "0.9"},
                               {"keep", "0.1"}});
  std::vector<std::string> expected = {"q", "-t", "10", "-o", "out.ply x", "in.ply", "r=0.9,k=0.1"};
  EXPECT_EQ(words, expected);
  auto s = create_simplifier("external");
  EXPECT_THROW(s->set_option("command", "q {nope}"), InvalidInput);
  EXPECT_THROW(s->set_option("command", "q 'open"), InvalidInput);
  EXPECT_THROW(s->set_option("output_format", "stl"), InvalidInput);
  EXPECT_THROW(s->set_option("timeout", "0"), InvalidInput);
}

}  // namespace
}  // namespace meshdev
