#!/bin/bash
# Regenerates results/paper/: the Fig. 8 sweep (sweep.csv, sweep.json, plots/) and Table 1
# (table1_*.txt / .json) on the armadillo and bunny scans of Debian's CGAL data.
#   bash results/paper/reproduce.sh [MESHDEV] [JOBS]     (default: build/apps/meshdev, 2)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
meshdev=$(realpath "${1:-$here/../../build/apps/meshdev}")
jobs=${2:-2}
cd "$here"
mkdir -p data
tar -xzf /usr/share/doc/libcgal-demo/data.tar.gz -C data --strip-components=2 \
  data/meshes/armadillo.off data/meshes/bunny00.off

# Fig. 8: every backend x 6 ratios x 2 meshes, default sampling (vertices + scan conversion,
# 10 x faces per direction), uniform-average vertex normals as in the paper.
start=$(date +%s)
"$meshdev" sweep paper.json --jobs "$jobs" --no-progress
echo "sweep: $(( $(date +%s) - start )) s"

# Table 1: mesh characteristics and deviation statistics of one pair per scan, the QSlim-like
# backend at 94 % (the paper's example pair: 93,752 -> 5,624 faces, 94.0 %).
for m in armadillo bunny00; do
  "$meshdev" simplify "data/$m.off" "data/${m}_cgal-gh_94.ply" --method cgal-gh --ratio 0.94
  "$meshdev" compare "data/$m.off" "data/${m}_cgal-gh_94.ply" --normals uniform \
    --attributes geometry,normal --json "table1_$m.json" > "table1_$m.txt"
done
"$meshdev" plot sweep.csv --log --relative --measures geometry,normal --out plots-log
rm -rf data
echo "done: $(( $(date +%s) - start )) s"
