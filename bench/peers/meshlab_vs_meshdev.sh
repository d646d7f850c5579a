#!/usr/bin/env bash
# Whole-process timing: `meshdev compare A B --sampling montecarlo --sample-count N --threads 2 -q`
# (both directions, N area-uniform face samples each way) against meshlabserver's "Hausdorff
# Distance" filter run twice (A->B and B->A), SampleFace only, SampleNum = N, MaxDist far above
# any distance so no sample is dropped. Best of R runs each; prints the ratio.
#
# meshdev is timed twice: with its default measures (geometry, normal, normal angle: more work
# than MeshLab's filter, which computes distances only) and with `--attributes geometry` (the
# same quantity as MeshLab's: the like-for-like ratio).
#
# MeshLab is timed two ways:
#   xvfb  - `xvfb-run -a meshlabserver ...` (what a user runs headless; includes X startup)
#   warm  - meshlabserver against a persistent Xvfb started here (no X startup; MeshLab's best)
# The ratio is meshlab / meshdev wall time (> 1: meshdev faster).
#
# usage: bench/peers/meshlab_vs_meshdev.sh [-n N] [-r R] [-o CSV] [-b BUILD_DIR] A B [A B ...]
#   defaults: N = 1000000, R = 3, BUILD_DIR = build-peers. Feed OFF or PLY (MeshLab 2020.09's OBJ
#   importer aborts in Debian 12). Needs: apt-get install -y meshlab xvfb xauth
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
n=1000000 reps=3 csv="" build="$repo/build-peers"
while getopts "n:r:o:b:" opt; do
  case $opt in
    n) n=$OPTARG ;; r) reps=$OPTARG ;; o) csv=$OPTARG ;; b) build=$OPTARG ;;
    *) sed -n '2,20p' "$0"; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
(( $# >= 2 && $# % 2 == 0 )) || { sed -n '2,20p' "$0"; exit 2; }
meshdev="$build/apps/meshdev"
[[ -x "$meshdev" ]] || { echo "missing $meshdev (make -j2 meshdev in $build)" >&2; exit 1; }
if ! command -v meshlabserver >/dev/null || ! command -v xvfb-run >/dev/null || ! command -v xauth >/dev/null; then
  DEBIAN_FRONTEND=noninteractive apt-get install -y meshlab xvfb xauth >/dev/null
fi

tmp="$(mktemp -d /tmp/meshlab_vs_meshdev.XXXXXX)"
xvfb_pid=""
cleanup() { [[ -n "$xvfb_pid" ]] && kill "$xvfb_pid" 2>/dev/null || true; rm -rf "$tmp"; }
trap cleanup EXIT

# A persistent X server for the "warm" runs (killed by its pid on exit).
display=""
for d in $(seq 90 120); do
  if [[ ! -e /tmp/.X$d-lock && ! -e /tmp/.X11-unix/X$d ]]; then display=":$d"; break; fi
done
Xvfb "$display" -screen 0 640x480x24 -nolisten tcp >/dev/null 2>&1 &
xvfb_pid=$!
sleep 1

# Every parameter of the filter must be present (simplifiers.md §5), or meshlabserver aborts.
write_mlx() {  # OUT N MAXDIST
  local filter
  filter() {
    cat <<XML
 <filter name="Hausdorff Distance">
  <Param type="RichMesh" value="$1" name="SampledMesh"/>
  <Param type="RichMesh" value="$2" name="TargetMesh"/>
  <Param type="RichBool" value="false" name="SaveSample"/>
  <Param type="RichBool" value="false" name="SampleVert"/>
  <Param type="RichBool" value="false" name="SampleEdge"/>
  <Param type="RichBool" value="false" name="SampleFauxEdge"/>
  <Param type="RichBool" value="true" name="SampleFace"/>
  <Param type="RichInt" value="$3" name="SampleNum"/>
  <Param type="RichAbsPerc" value="$4" min="0" max="$4" name="MaxDist"/>
 </filter>
XML
  }
  { echo '<!DOCTYPE FilterScript>'; echo '<FilterScript>'
    filter 0 1 "$2" "$3"; filter 1 0 "$2" "$3"; echo '</FilterScript>'; } > "$1"
}

diag() { "$meshdev" info "$1" | awk '$1 == "bbox" {print $3; exit}'; }
faces() { "$meshdev" info "$1" | awk '$1 == "triangles" {print $2; exit}'; }

# Runs "$@" R times; prints "best_wall max_rss_mib" (wall to the microsecond from bash's clock
# around /usr/bin/time, which gives the peak RSS; its own %e has 10 ms steps).
best_of() {
  local best="" rss=0 out t0 t1 wall
  for ((i = 0; i < reps; i++)); do
    t0=$EPOCHREALTIME
    /usr/bin/time -f "%M" -o "$tmp/time" "$@" >"$tmp/stdout" 2>"$tmp/stderr" || {
      echo "FAILED: $*" >&2; tail -5 "$tmp/stderr" >&2; return 1; }
    t1=$EPOCHREALTIME
    wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.3f", b - a}')
    out=$(tail -1 "$tmp/time")
    best=$(awk -v a="$best" -v b="$wall" 'BEGIN {print (a == "" || b < a) ? b : a}')
    rss=$(awk -v a="$rss" -v b="$out" 'BEGIN {print (b / 1024 > a) ? b / 1024 : a}')
  done
  echo "$best $rss"
}

header="a,b,a_faces,b_faces,samples_per_direction,repeats,meshdev_s,meshdev_rss_mib,meshlab_xvfb_s,meshlab_warm_s,meshlab_rss_mib,ratio_xvfb,ratio_warm,meshdev_mean_ab,meshlab_mean_ab,meshdev_mean_ba,meshlab_mean_ba,meshlab_samples_ab,load_start,load_end,meshdev_geometry_s,ratio_geometry_xvfb,ratio_geometry_warm"
[[ -n "$csv" && ! -s "$csv" ]] && echo "$header" > "$csv"
printf "%-22s %-22s %9s %9s %9s %9s %9s %9s %8s %8s %8s %8s\n" A B "meshdev s" "MD geom s" \
  "ML xvfb s" "ML warm s" "MD MiB" "ML MiB" "x xvfb" "x warm" "geom xvf" "geom wrm"
while (( $# )); do
  a=$1 b=$2; shift 2
  load0=$(cut -d' ' -f1 /proc/loadavg)
  maxdist=$(awk -v x="$(diag "$a")" -v y="$(diag "$b")" 'BEGIN {printf "%g", 10 * (x + y)}')
  write_mlx "$tmp/hausdorff.mlx" "$n" "$maxdist"
  read -r md_s md_rss < <(best_of "$meshdev" compare "$a" "$b" --sampling montecarlo \
    --sample-count "$n" --threads 2 -q)
  read -r mdg_s _ < <(best_of "$meshdev" compare "$a" "$b" --sampling montecarlo \
    --sample-count "$n" --threads 2 -q --attributes geometry)
  read -r mlx_s ml_rss < <(best_of xvfb-run -a meshlabserver -i "$a" -i "$b" -s "$tmp/hausdorff.mlx")
  # warm: same command against the persistent X server (meshlabserver appends to its -l log)
  rm -f "$tmp/ml.log"
  read -r mlw_s ml_rss2 < <(DISPLAY="$display" best_of meshlabserver -i "$a" -i "$b" -s "$tmp/hausdorff.mlx" -l "$tmp/ml.log")
  ml_rss=$(awk -v a="$ml_rss" -v b="$ml_rss2" 'BEGIN {print (a > b) ? a : b}')
  # Agreement (untimed): MeshLab's mean per direction from its log, meshdev's from --csv.
  # The -l log holds, per direction: "Sampled N pts ..." then "min : x max y mean : z RMS : w".
  # (the log repeats earlier blocks: keep the first block of each direction)
  ml_means=$(awk '/Sampled [0-9]+ pts/ {want = !seen[$0]++; next}
    want && /min :/ {print $8; want = 0}' \
    "$tmp/ml.log" | tr '\n' ' ')
  ml_samples=$(awk '/Sampled [0-9]+ pts/ {print $2; exit}' "$tmp/ml.log")
  "$meshdev" compare "$a" "$b" --sampling montecarlo --sample-count "$n" --threads 2 -q \
    --csv "$tmp/md.csv" >/dev/null
  md_means=$(python3 - "$tmp/md.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
out = []
for r in rows:
    if r.get("measure") == "geometry" and r.get("direction") != "symmetric":
        out.append(r.get("mean", ""))
print(" ".join(out[:2]) if out else "? ?")
PY
)
  read -r md_ab md_ba <<<"$md_means"
  read -r ml_ab ml_ba <<<"${ml_means:-? ?}"
  load1=$(cut -d' ' -f1 /proc/loadavg)
  rx=$(awk -v m="$md_s" -v l="$mlx_s" 'BEGIN {printf "%.2f", l / m}')
  rw=$(awk -v m="$md_s" -v l="$mlw_s" 'BEGIN {printf "%.2f", l / m}')
  gx=$(awk -v m="$mdg_s" -v l="$mlx_s" 'BEGIN {printf "%.2f", l / m}')
  gw=$(awk -v m="$mdg_s" -v l="$mlw_s" 'BEGIN {printf "%.2f", l / m}')
  printf "%-22s %-22s %9.3f %9.3f %9.3f %9.3f %9.0f %9.0f %8s %8s %8s %8s\n" "$(basename "$a")" \
    "$(basename "$b")" "$md_s" "$mdg_s" "$mlx_s" "$mlw_s" "$md_rss" "$ml_rss" "$rx" "$rw" "$gx" "$gw"
  echo "    mean distance A->B: meshdev $md_ab, MeshLab $ml_ab; B->A: meshdev $md_ba, MeshLab $ml_ba;" \
       "MeshLab sampled ${ml_samples:-?} pts per direction; load $load0 -> $load1"
  [[ -n "$csv" ]] && echo "$(basename "$a"),$(basename "$b"),$(faces "$a"),$(faces "$b"),$n,$reps,$md_s,$md_rss,$mlx_s,$mlw_s,$ml_rss,$rx,$rw,$md_ab,$ml_ab,$md_ba,$ml_ba,${ml_samples:-},$load0,$load1,$mdg_s,$gx,$gw" >> "$csv"
done
