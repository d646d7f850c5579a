#!/bin/bash
# install_test.sh BUILD_DIR EXTERNAL_SRC SCRATCH CMAKE: installs BUILD_DIR into SCRATCH/prefix,
# then configures, builds and runs the external project against it (find_package(meshdev)).
set -euo pipefail
build=$1 src=$2 scratch=$3 cmake=$4
rm -rf "$scratch" && mkdir -p "$scratch"
"$cmake" --install "$build" --prefix "$scratch/prefix" >"$scratch/install.log"
test -f "$scratch/prefix/lib/cmake/meshdev/meshdevConfig.cmake"
test -f "$scratch/prefix/include/meshdev/harness/testing/deviation_assertions.h"
"$cmake" -S "$src" -B "$scratch/build" -DCMAKE_PREFIX_PATH="$scratch/prefix" \
  -DCMAKE_BUILD_TYPE=Release >"$scratch/configure.log"
"$cmake" --build "$scratch/build" -j 2 >"$scratch/build.log"
"$scratch/build/consumer_test"
echo "install_test: find_package(meshdev) + EXPECT_SYMMETRIC_DEVIATION_AT_MOST: ok"
