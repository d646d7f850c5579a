// Compare two meshes and print the symmetric geometric and normal deviation.
// Usage: quickstart A.off B.off
#include <iostream>

#include "metric/metric.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: quickstart A B\n";
    return 2;
  }
  try {
    meshdev::TriMesh a = meshdev::read_mesh(argv[1]);
    meshdev::TriMesh b = meshdev::read_mesh(argv[2]);
    meshdev::CompareOptions options;         // vertices + scan-converted faces, both ways
    options.sampling.target_count = 200000;  // face samples per direction
    meshdev::ComparisonResult r = meshdev::compare_meshes(a, b, options, argv[1], argv[2]);
    for (std::size_t m = 0; m < r.measures.size(); ++m)
      std::cout << r.measures[m].name << ": mean " << r.symmetric[m].mean << ", Hausdorff "
                << r.symmetric[m].hausdorff << " (" << r.measures[m].unit << ")\n";
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
