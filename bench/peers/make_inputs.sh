#!/usr/bin/env bash
# Generates the peer-comparison inputs (never inside the repository's tracked tree; shared data is
# read in place, never copied into the repo):
#   generated bumpy tori:  torus100k.ply (exactly 100,000 faces), torus1m.ply (exactly 1,000,000)
#   their simplifications: torus100k_s10k.ply, torus1m_s100k.ply   (meshdev simplify, meshopt)
#   torus1m_shuffled.ply:  torus1m with its faces in a random order (seed 1), for the cost of a
#                          reference whose face order has no locality (not one of the pairs)
#   real meshes:           armadillo.off + armadillo_s5k.ply, bunny00.off + bunny00_s7k.ply
#                          (Debian's libcgal-demo data), buildings.ply + buildings_s40k.ply
#                          (../shared/data/large/buildings.obj, converted to PLY for MeshLab)
# and writes pairs.txt: "label A B" per pair (A = sampled mesh, B = searched mesh).
#
# usage: bench/peers/make_inputs.sh [BUILD_DIR] [OUT_DIR]
#   BUILD_DIR  a build with -DMESHDEV_BUILD_BENCH=ON -DMESHDEV_BUILD_PEERS=ON (default build-peers)
#   OUT_DIR    default BUILD_DIR/peer_inputs
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
build="$(cd "${1:-$repo/build-peers}" && pwd)"
out="${2:-$build/peer_inputs}"
mkdir -p "$out"
tool="$build/bench/peers/peer_mesh_tool"
meshdev="$build/apps/meshdev"
shared="${MESHDEV_SHARED_DATA_DIR:-$repo/../shared/data}"
cgal_data=/usr/share/doc/libcgal-demo/data.tar.gz
for exe in "$tool" "$meshdev"; do
  [[ -x "$exe" ]] || { echo "missing $exe (make -j2 peer_mesh_tool meshdev in $build)" >&2; exit 1; }
done

faces() {  # face count of a PLY/OFF we wrote or got
  "$meshdev" info "$1" 2>/dev/null | awk '$1 == "triangles" {print $2; exit}'
}
simplify() {  # IN OUT FACES
  if [[ ! -s "$2" ]]; then
    "$meshdev" simplify "$1" "$2" --method meshopt --faces "$3" >/dev/null
    # meshdev writes double positions; rewrite as float PLY so all tools read the same numbers.
    "$tool" convert "$2" "$2.tmp.ply" >/dev/null && mv "$2.tmp.ply" "$2"
  fi
  echo "  $(basename "$2"): $(faces "$2") faces (target $3)"
}

echo "generated tori -> $out"
[[ -s "$out/torus100k.ply" ]] || "$tool" torus 500 100 "$out/torus100k.ply" >/dev/null
[[ -s "$out/torus1m.ply" ]] || "$tool" torus 1000 500 "$out/torus1m.ply" >/dev/null
echo "  torus100k.ply: $(faces "$out/torus100k.ply") faces"
echo "  torus1m.ply: $(faces "$out/torus1m.ply") faces"
[[ -s "$out/torus1m_shuffled.ply" ]] ||
  "$tool" shuffle "$out/torus1m.ply" "$out/torus1m_shuffled.ply" 1 >/dev/null
simplify "$out/torus100k.ply" "$out/torus100k_s10k.ply" 10000
simplify "$out/torus1m.ply" "$out/torus1m_s100k.ply" 100000

{
  echo "torus100k->10k $out/torus100k.ply $out/torus100k_s10k.ply"
  echo "torus100k->1m $out/torus100k.ply $out/torus1m.ply"
  echo "torus1m->100k $out/torus1m.ply $out/torus1m_s100k.ply"
} > "$out/pairs.txt"

echo "real meshes"
if [[ -f "$cgal_data" ]]; then
  for m in armadillo bunny00; do
    [[ -s "$out/$m.off" ]] || tar -xzf "$cgal_data" -O "data/meshes/$m.off" > "$out/$m.off"
  done
  echo "  armadillo.off: $(faces "$out/armadillo.off") faces"
  echo "  bunny00.off: $(faces "$out/bunny00.off") faces"
  simplify "$out/armadillo.off" "$out/armadillo_s5k.ply" 5200
  simplify "$out/bunny00.off" "$out/bunny00_s7k.ply" 7540
  echo "armadillo->5k $out/armadillo.off $out/armadillo_s5k.ply" >> "$out/pairs.txt"
  echo "bunny00->7k $out/bunny00.off $out/bunny00_s7k.ply" >> "$out/pairs.txt"
else
  echo "  $cgal_data absent (apt-get install -y libcgal-demo): skipped" >&2
fi
if [[ -f "$shared/large/buildings.obj" ]]; then
  [[ -s "$out/buildings.ply" ]] || "$tool" convert "$shared/large/buildings.obj" "$out/buildings.ply" >/dev/null
  echo "  buildings.ply: $(faces "$out/buildings.ply") faces"
  simplify "$out/buildings.ply" "$out/buildings_s40k.ply" 40000
  echo "buildings->40k $out/buildings.ply $out/buildings_s40k.ply" >> "$out/pairs.txt"
else
  echo "  $shared/large/buildings.obj absent: skipped" >&2
fi
echo "pairs: $out/pairs.txt"
cat "$out/pairs.txt"
