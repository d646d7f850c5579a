#!/usr/bin/env bash
# Instructions per sample of meshdev's deviation loop (closest point with ties, geometry, normal,
# normal angle and a temperature, as peer_compare times it) counted by callgrind, against the
# baseline in bench/peers/instructions_per_sample.txt. Unlike a time, the count does not move
# with the host's load or clock, so it guards the query engine against regressions in CI
# (bench/smoke.sh) where a timed check could not (docs/performance.md §1, "Instruction guard").
#
# usage: bench/peers/instructions_per_sample.sh BUILD_DIR [--update]
#   BUILD_DIR: a Release build with peer_compare (MESHDEV_BUILD_PEERS) whose peer_inputs/ holds
#   the generated tori (bench/peers/make_inputs.sh BUILD_DIR).
#   --update: rewrite the baseline with this run's counts (after a change measured to pay, or
#   when a new compiler changes the code).
# For each pair: `valgrind --tool=callgrind --toggle-collect='meshdev::compute_deviations*'
# peer_compare A B N --repeats 1 --engines meshdev --threads 1` (one thread: the count is the
# same in every run), the collected count divided by the samples. Exit 1 where a pair takes more
# than TOLERANCE (default 0.02) above its baseline; a pair more than that below it is reported
# (the baseline then wants --update). Exit 0 without counting, with the reason, where valgrind
# is missing or the CPU lacks AVX2 or FMA (the counts are those of meshdev's default AVX2
# kernels; AVX-512 is opt-in, and valgrind runs none).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build="${1:?usage: $0 BUILD_DIR [--update]}"
update="${2:-}"
baseline="$here/bench/peers/instructions_per_sample.txt"
tolerance="${TOLERANCE:-0.02}"
pc="$build/bench/peers/peer_compare"
in="$build/peer_inputs"

if ! command -v valgrind >/dev/null; then
  echo "instructions_per_sample: skipped, valgrind is not installed (apt-get install valgrind)"
  exit 0
fi
if ! grep -qw avx2 /proc/cpuinfo || ! grep -qw fma /proc/cpuinfo; then
  echo "instructions_per_sample: skipped, this CPU lacks AVX2 or FMA (the baseline counts the AVX2 kernels)"
  exit 0
fi
[[ -x "$pc" ]] || { echo "instructions_per_sample: no $pc" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
new=()
while read -r a b n base; do
  [[ -z "$a" ]] && continue  # a blank line (comments are filtered below)
  [[ -s "$in/$a" && -s "$in/$b" ]] || { echo "instructions_per_sample: missing $in/$a or $in/$b" >&2; exit 2; }
  valgrind --tool=callgrind --callgrind-out-file="$work/out" \
    --toggle-collect='meshdev::compute_deviations*' \
    "$pc" "$in/$a" "$in/$b" "$n" --repeats 1 --engines meshdev --threads 1 >"$work/log" 2>&1 || {
    tail -n 20 "$work/log"
    echo "instructions_per_sample: peer_compare failed under valgrind ($a -> $b)" >&2
    exit 2
  }
  total=$(sed -n 's/^summary: //p' "$work/out")
  samples=$(awk '$2 == "samples" && $3 == "on" && $4 == "A" { print $1; exit }' "$work/log")
  [[ -n "$total" && -n "$samples" ]] || { echo "instructions_per_sample: no count for $a -> $b" >&2; exit 2; }
  per=$(awk -v t="$total" -v s="$samples" 'BEGIN { printf "%.1f", t / s }')
  verdict=$(awk -v p="$per" -v b="$base" -v tol="$tolerance" 'BEGIN {
    if (b <= 0) { print "ABOVE (no baseline)"; exit }
    r = p / b
    printf "%s %.4f\n", (r > 1 + tol ? "ABOVE" : (r < 1 - tol ? "below" : "ok")), r }')
  printf '%-22s -> %-22s %8d samples: %8.1f instructions per sample, baseline %s (%s)\n' \
    "$a" "$b" "$samples" "$per" "$base" "$verdict"
  case $verdict in
    ABOVE*) status=1 ;;
    below*) echo "   fewer than the baseline: if this is a change of yours, run with --update" ;;
  esac
  new+=("$a $b $n $per")
done < <(grep -v '^#' "$baseline")

if [[ "$update" == --update ]]; then
  { grep '^#' "$baseline"; printf '%s\n' "${new[@]}"; } >"$work/baseline"
  cp "$work/baseline" "$baseline"
  echo "instructions_per_sample: baseline rewritten: $baseline"
  exit 0
fi
if [[ $status -ne 0 ]]; then
  echo "instructions_per_sample: a pair takes more than $tolerance above its baseline ($baseline):" \
    "measure the change's time (peer_compare --ab, docs/performance.md §1) and, if it is meant," \
    "run this script with --update" >&2
fi
exit $status
