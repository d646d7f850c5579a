#!/usr/bin/env bash
# meshdev's one entry point for a fresh Debian 12 machine (README "Quick start").
#   bash scripts/quickstart.sh demo   install what is missing, build, compare a real scan with a
#                                     simplified copy; outputs in results/demo/
#   bash scripts/quickstart.sh test   install what is missing, build, run the whole test suite
#   bash scripts/quickstart.sh build  install what is missing and build only
# Idempotent: apt-get runs only when a package is missing; the build is incremental.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${MESHDEV_BUILD_DIR:-$here/build}"
jobs="${MESHDEV_JOBS:-$(nproc)}"

# Build and test dependencies, all from Debian 12.
packages=(
  build-essential cmake pkg-config git
  libopenmesh-dev libopenmesh-apps libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev
  nlohmann-json3-dev libmeshoptimizer-dev libcgal-dev libeigen3-dev
  libcgal-demo libstb-dev python3 python3-matplotlib python3-vtk9 meshlab xvfb xauth
)

source "$here/scripts/install_packages.sh"
setup() { install_packages "${packages[@]}"; }

build() {
  echo "== building in $build"
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release ${MESHDEV_CMAKE_ARGS:-} >/dev/null
  cmake --build "$build" -j "$jobs"
}

demo() {
  local out="$here/results/demo" meshdev="$build/apps/meshdev"
  mkdir -p "$out"
  # A real scan from Debian's CGAL data: the Stanford bunny (bunny00.off, 75,408 faces).
  tar -xzf /usr/share/doc/libcgal-demo/data.tar.gz -C "$out" --strip-components=2 data/meshes/bunny00.off
  echo "== simplifying bunny00.off to 10 % of its faces (OpenMesh quadric decimation)"
  "$meshdev" simplify "$out/bunny00.off" "$out/bunny00_10.ply" --method openmesh-quadric --ratio 0.9
  echo "== meshdev compare bunny00.off bunny00_10.ply"
  "$meshdev" compare "$out/bunny00.off" "$out/bunny00_10.ply" \
    --json "$out/compare.json" --csv "$out/compare.csv" --colored "$out/bunny00_deviation.ply"
  echo "== meshdev sweep: 3 simplifiers (QSlim-, Jade-, ProgMesh-like) x 3 reduction ratios"
  (cd "$out" && "$meshdev" sweep --mesh bunny00.off \
    --simplifiers cgal-gh,openmesh-hausdorff,openmesh-quadric --ratios 50,90,98 \
    --sample-count 200000 --jobs "$jobs" --out sweep)
  echo "== outputs in $out: compare.json, compare.csv, bunny00_deviation.ply (open it in MeshLab),"
  echo "   sweep/sweep.csv (one row per simplifier x ratio x measure), sweep/plots/bunny00_fig8.png"
}

run_tests() {
  echo "== running the test suite"
  cd "$build" && ctest --output-on-failure -j "$jobs"
}

case "${1:-}" in
  demo) setup; build; demo ;;
  test) setup; build; run_tests ;;
  build) setup; build ;;
  *) echo "usage: $0 demo|test|build" >&2; exit 2 ;;
esac
