#!/usr/bin/env sh
# Runs examples/quickstart on two real meshes from Debian's CGAL data (skips with 77 if absent).
set -eu
bin=$1 work=$2
archive=/usr/share/doc/libcgal-demo/data.tar.gz
if [ ! -f "$archive" ]; then
  echo "SKIP: $archive not found (install libcgal-demo)"
  exit 77
fi
mkdir -p "$work"
tar -xzf "$archive" -C "$work" data/meshes/anchor_dense.off data/meshes/anchor.off
"$bin" "$work/data/meshes/anchor_dense.off" "$work/data/meshes/anchor.off"
