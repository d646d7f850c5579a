#include "tests/support/test_data.h"

#include <cstdlib>
#include <filesystem>
#include <mutex>

namespace fs = std::filesystem;

namespace meshdev::test {

std::string shared_data_dir() {
  if (const char* env = std::getenv("MESHDEV_SHARED_DATA")) return fs::is_directory(env) ? env : "";
  fs::path dir = MESHDEV_SHARED_DATA_DIR;
  return fs::is_directory(dir) ? fs::weakly_canonical(dir).string() : std::string();
}

std::string cgal_mesh(const std::string& name) {
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  const fs::path archive = MESHDEV_CGAL_DATA_ARCHIVE;
  const fs::path root = fs::path(MESHDEV_TEST_TMP_DIR) / "cgal";
  const fs::path file = root / "data" / "meshes" / name;
  if (fs::exists(file)) return file.string();
  if (!fs::exists(archive)) return "";
  fs::create_directories(root);
  std::string cmd = "tar -xzf '" + archive.string() + "' -C '" + root.string() + "' 'data/meshes/" +
                    name + "' 2>/dev/null";
  if (std::system(cmd.c_str()) != 0 || !fs::exists(file)) return "";
  return file.string();
}

std::string scratch_dir(const std::string& test_name) {
  fs::path dir = fs::path(MESHDEV_TEST_TMP_DIR) / "scratch" / test_name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

}  // namespace meshdev::test
