#!/usr/bin/env bash
# Builds and runs the whole peer comparison, writing
#   results/performance/peers.csv     one row per (series, pair, engine, threads) from peer_compare
#   results/performance/rounds.csv    the pairs' interleaved rounds, one row per (pair, round, threads)
#   results/performance/host.csv      bench/peers/host_probe before and after the pairs: the host's
#                                     arithmetic, memory latency and bandwidth on 1 and 2 threads
#   results/performance/meshlab.csv   whole-process meshdev compare vs meshlabserver
#   results/performance/peers.png     throughput vs faces of B and vs samples (matplotlib)
#   results/performance/peers_per_cpu.png  the same per CPU-second (fair on a loaded machine)
#   results/performance/peers.log     everything printed, ending with issue 3's targets against
#                                     this run (bench/peers/table_md.py --targets)
# Series: "pairs" (the issue's pairs and the real meshes), "faces" (A = torus100k, B = bumpy tori
# from 10k to 1M faces), "samples" (torus100k -> 10k with 100k..3M samples).
#
# usage: bench/peers/run_all.sh            (env: BUILD=build-peers N=1000000 REPEATS=3 ROUNDS=5
#                                            QUICK=1 for a smoke run: N=200000 unless given,
#                                            one repeat, one round; SKIP_MESHLAB=1;
#                                            OUT=results/performance; CHECK=1e-6)
# CHECK: every peer_compare run is also a cross-check (peer_compare --check): the script stops
# with an error if meshdev, Embree and CGAL give per-sample distances more than CHECK times B's
# diagonal apart. OUT: where the files above go (bench/smoke.sh, run by CI, writes elsewhere).
# ROUNDS: the pairs are also timed in interleaved rounds (peer_compare --rounds: meshdev, Embree
# and Embree+hint one run each per round and thread count, 1 and 2 threads in the same round),
# whose median ratios (to Embree, and 2 threads to 1) hold on a host whose speed drifts.
# Needs: apt-get install -y libembree-dev libcgal-dev libtbb-dev libbenchmark-dev meshlab xvfb xauth
# The machine should be quiet: every loop prints its CPU share and the load average.
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
build="${BUILD:-$repo/build-peers}"
n="${N:-1000000}" reps="${REPEATS:-3}" rounds="${ROUNDS:-5}" check="${CHECK:-1e-6}"
[[ "${QUICK:-0}" == 1 ]] && n="${N:-200000}" reps=1 rounds=1
out="${OUT:-$repo/results/performance}"
mkdir -p "$out" "$build"
log="$out/peers.log"
: > "$log"
say() { echo "$@" | tee -a "$log"; }

say "== build ($build)"
cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release -DMESHDEV_BUILD_BENCH=ON \
  -DMESHDEV_BUILD_PEERS=ON -DMESHDEV_BUILD_TESTS=OFF -DMESHDEV_BUILD_EXAMPLES=OFF >>"$log" 2>&1
make -C "$build" -j2 peer_compare peer_mesh_tool host_probe meshdev >>"$log" 2>&1
probe() {  # the host's state now (bench/peers/host_probe.cpp), into the log and host.csv
  say "== host_probe ($1)"
  "$build/bench/peers/host_probe" --rounds "$probe_rounds" --csv "$out/host.csv" 2>&1 | tee -a "$log"
}
probe_rounds=5
[[ "${QUICK:-0}" == 1 ]] && probe_rounds=1
rm -f "$out/host.csv"

say "== inputs"
"$repo/bench/peers/make_inputs.sh" "$build" 2>&1 | tee -a "$log"
in="$build/peer_inputs"
tool="$build/bench/peers/peer_mesh_tool"
# Face-scaling targets: tori on a different grid from torus100k (500 x 100), so distances are real.
for g in "100 50" "224 112" "316 158" "500 250"; do
  set -- $g
  f=$((2 * $1 * $2))
  [[ -s "$in/torusB_$f.ply" ]] || "$tool" torus "$1" "$2" "$in/torusB_$f.ply" >/dev/null
done

csv="$out/peers.csv"
rounds_csv="$out/rounds.csv"
rm -f "$csv" "$rounds_csv"
pc="$build/bench/peers/peer_compare"
probe "before the pairs"
say "== peer_compare: N=$n, best of $reps, load average $(cut -d' ' -f1-3 /proc/loadavg)"
while read -r label a b; do
  say "-- pairs|$label"
  "$pc" "$a" "$b" "$n" --repeats "$reps" --embree-hint --rounds "$rounds" --label "pairs|$label" \
    --check "$check" --csv "$csv" --rounds-csv "$rounds_csv" 2>&1 | sed '/^CSV$/,$d' | tee -a "$log"
done < "$in/pairs.txt"
probe "after the pairs"
for f in 10000 50176 99856 250000; do
  say "-- faces|torus100k->$f"
  "$pc" "$in/torus100k.ply" "$in/torusB_$f.ply" "$n" --repeats "$reps" --embree-hint \
    --label "faces|torus100k->$f" --check "$check" --csv "$csv" 2>&1 | sed '/^CSV$/,$d' | tee -a "$log"
done
say "-- faces|torus100k->1000000 (= pairs|torus100k->1m)"
grep '^pairs|torus100k->1m,' "$csv" | sed 's/^pairs|torus100k->1m,/faces|torus100k->1000000,/' >> "$csv"
for s in 100000 300000 1000000 3000000; do
  [[ "${QUICK:-0}" == 1 && $s -gt 300000 ]] && continue
  say "-- samples|torus100k->10k N=$s"
  "$pc" "$in/torus100k.ply" "$in/torus100k_s10k.ply" "$s" --repeats "$reps" \
    --label "samples|torus100k->10k" --check "$check" --csv "$csv" 2>&1 | sed '/^CSV$/,$d' | tee -a "$log"
done

if [[ "${SKIP_MESHLAB:-0}" != 1 ]]; then
  say "== meshdev compare vs meshlabserver (whole process, N=$n per direction, best of $reps)"
  rm -f "$out/meshlab.csv"
  real=()
  while read -r label a b; do
    case $label in torus*) ;; *) real+=("$a" "$b") ;; esac
  done < "$in/pairs.txt"
  "$repo/bench/peers/meshlab_vs_meshdev.sh" -n "$n" -r "$reps" -o "$out/meshlab.csv" -b "$build" \
    "${real[@]}" 2>&1 | tee -a "$log"
fi

say "== plot"
/usr/bin/python3 "$repo/bench/peers/plot_peers.py" "$csv" "$out/peers.png" wall 2>&1 | tee -a "$log"
/usr/bin/python3 "$repo/bench/peers/plot_peers.py" "$csv" "$out/peers_per_cpu.png" cpu 2>&1 | tee -a "$log"
say "== the pairs' rounds (medians)"
/usr/bin/python3 "$repo/bench/peers/table_md.py" --rounds "$rounds_csv,$csv" 2>&1 | tee -a "$log"
say "== issue 3's targets against this run (docs/performance.md)"
meshlab_csv=()
[[ "${SKIP_MESHLAB:-0}" != 1 && -s "$out/meshlab.csv" ]] && meshlab_csv=("$out/meshlab.csv")
/usr/bin/python3 "$repo/bench/peers/table_md.py" --targets "$rounds_csv" "$csv" "$log" \
  "${meshlab_csv[@]}" 2>&1 | tee -a "$log"
say "done: $csv $rounds_csv $out/peers.png $log (load average now $(cut -d' ' -f1-3 /proc/loadavg))"
