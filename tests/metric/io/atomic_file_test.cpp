#include "metric/io/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "metric/errors.h"
#include "metric/io/write_ply.h"
#include "tests/support/shapes.h"
#include "tests/support/test_data.h"

namespace fs = std::filesystem;

namespace meshdev::test {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Files in `dir` other than the expected ones (left-over temporaries).
std::size_t file_count(const std::string& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.is_regular_file() ? 1 : 0;
  return n;
}

void expect_write_error(const std::function<void()>& f, const std::string& path,
                        const std::string& text) {
  try {
    f();
    ADD_FAILURE() << "no WriteError for " << path;
  } catch (const WriteError& e) {
    std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(text), std::string::npos) << "expected '" << text << "' in: " << what;
  }
}

TEST(AtomicFile, WritesAndReplaces) {
  std::string dir = scratch_dir("atomic_basic");
  std::string path = dir + "/out.txt";
  write_file_atomically(path, [](std::ostream& out) { out << "first"; });
  EXPECT_EQ(slurp(path), "first");
  write_file_atomically(path, [](std::ostream& out) {
    for (int i = 0; i < 100000; ++i) out << "0123456789";  // more than the 64 KiB buffer
  });
  EXPECT_EQ(slurp(path).size(), 1000000u);
  EXPECT_EQ(file_count(dir), 1u);
}

TEST(AtomicFile, MissingFolderIsAWriteError) {
  std::string path = scratch_dir("atomic_missing") + "/no/such/folder/out.ply";
  expect_write_error([&] { write_file_atomically(path, [](std::ostream& out) { out << "x"; }); },
                     path, "No such file or directory");
  EXPECT_FALSE(fs::exists(path));
}

TEST(AtomicFile, DiskFullThroughSymlinkToDevFull) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "/dev/full not available";
  std::string dir = scratch_dir("atomic_full");
  std::string link = dir + "/full.ply";
  fs::create_symlink("/dev/full", link);
  expect_write_error([&] { write_file_atomically(link, [](std::ostream& out) { out << "data"; }); },
                     link, "No space left on device");
  expect_write_error([&] { write_ply(link, tetrahedron()); }, link, "No space left on device");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(file_count(dir), 0u);
}

TEST(AtomicFile, FailedWriteKeepsTheOldFileAndRemovesTheTemporary) {
  std::string dir = scratch_dir("atomic_fsize");
  std::string path = dir + "/keep.txt";
  write_file_atomically(path, [](std::ostream& out) { out << "old"; });
  // Limit the file size to 1000 bytes: writes past it fail with EFBIG (SIGXFSZ ignored).
  struct rlimit saved {};
  getrlimit(RLIMIT_FSIZE, &saved);
  auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = saved;
  small.rlim_cur = 1000;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  try {
    write_file_atomically(path, [](std::ostream& out) { out << std::string(200000, 'x'); });
    ADD_FAILURE() << "no WriteError";
  } catch (const WriteError& e) {
    EXPECT_NE(std::string(e.what()).find("File too large"), std::string::npos) << e.what();
  }
  setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(slurp(path), "old");
  EXPECT_EQ(file_count(dir), 1u);
}

TEST(AtomicFile, ExceptionInBodyKeepsTheOldFile) {
  std::string dir = scratch_dir("atomic_throw");
  std::string path = dir + "/keep.txt";
  write_file_atomically(path, [](std::ostream& out) { out << "old"; });
  EXPECT_THROW(write_file_atomically(path,
                                     [](std::ostream& out) {
                                       out << "partial";
                                       throw std::runtime_error("boom");
                                     }),
               std::runtime_error);
  EXPECT_EQ(slurp(path), "old");
  EXPECT_EQ(file_count(dir), 1u);
}

TEST(AtomicFile, SymlinkToRegularFileReplacesTheTarget) {
  std::string dir = scratch_dir("atomic_link");
  write_file_atomically(dir + "/target.txt", [](std::ostream& out) { out << "old"; });
  fs::create_symlink(dir + "/target.txt", dir + "/link.txt");
  write_file_atomically(dir + "/link.txt", [](std::ostream& out) { out << "new"; });
  EXPECT_TRUE(fs::is_symlink(dir + "/link.txt"));
  EXPECT_EQ(slurp(dir + "/target.txt"), "new");
}

TEST(AtomicFile, DirectoryAsTargetIsAWriteError) {
  std::string dir = scratch_dir("atomic_dir");
  expect_write_error([&] { write_file_atomically(dir, [](std::ostream& out) { out << "x"; }); },
                     dir, "Is a directory");
}

// The check made before the work: a path in a missing folder, in a file taken for a folder, or
// that is a folder, is a WriteError naming it; a path in an existing folder, a bare file name
// (the working folder) and a device pass, and nothing is created.
TEST(AtomicFile, OutputPathIsCheckedBeforeTheWork) {
  const std::string dir = scratch_dir("atomic_check");
  const std::string missing = dir + "/no/such/folder/out.json";
  expect_write_error([&] { check_output_path(missing); }, missing, "No such file or directory");
  std::ofstream(dir + "/file.txt") << "x";
  const std::string under_file = dir + "/file.txt/out.json";
  expect_write_error([&] { check_output_path(under_file); }, under_file, "Not a directory");
  expect_write_error([&] { check_output_path(dir); }, dir, "Is a directory");
  EXPECT_NO_THROW(check_output_path(dir + "/out.json"));
  EXPECT_NO_THROW(check_output_path("out.json"));
  EXPECT_NO_THROW(check_output_path("/dev/null"));
  EXPECT_FALSE(fs::exists(dir + "/no"));
  EXPECT_FALSE(fs::exists(dir + "/out.json"));
}

// An output folder is made with its parents (and may exist already); a file in the way is a
// WriteError naming it.
TEST(AtomicFile, OutputFolderIsMadeWithItsParents) {
  const std::string dir = scratch_dir("atomic_folder");
  make_output_folder(dir + "/a/b/c");
  EXPECT_TRUE(fs::is_directory(dir + "/a/b/c"));
  EXPECT_NO_THROW(make_output_folder(dir + "/a/b/c"));
  std::ofstream(dir + "/file.txt") << "x";
  expect_write_error([&] { make_output_folder(dir + "/file.txt"); }, dir + "/file.txt",
                     "cannot create the folder");
  expect_write_error([&] { make_output_folder(dir + "/file.txt/d"); }, dir + "/file.txt/d",
                     "cannot create the folder");
}

}  // namespace
}  // namespace meshdev::test
