// harness_make_meshes DIR: writes icosphere3.ply (1280 faces) and grid12.ply (288 faces), the
// meshes the script tests sweep, built in code (tests/support/shapes.h).
#include <iostream>
#include <string>

#include "metric/io/write_ply.h"
#include "tests/support/shapes.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: harness_make_meshes DIR\n";
    return 2;
  }
  const std::string dir = argv[1];
  meshdev::write_ply(dir + "/icosphere3.ply", meshdev::test::icosphere(3));
  meshdev::write_ply(dir + "/grid12.ply", meshdev::test::grid(12));
  return 0;
}
