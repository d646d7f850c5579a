#pragma once
// Where optional real data lives. Tests that need it call GTEST_SKIP() with a clear message when
// it is absent (a clean clone without ../shared, or a machine without libcgal-demo).
#include <string>

namespace meshdev::test {

// ../shared/data beside the repository, or "" if absent.
std::string shared_data_dir();

// Path of data/meshes/<name> from libcgal-demo's data archive, extracted once into the build
// folder; "" if the package is not installed.
std::string cgal_mesh(const std::string& name);

// A fresh, empty scratch folder for one test (under the build folder).
std::string scratch_dir(const std::string& test_name);

}  // namespace meshdev::test
