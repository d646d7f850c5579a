#!/bin/bash
# A fake external simplifier for the fault-injection tests (external_process_test.cpp).
# usage: fake_simplifier.sh MODE INPUT OUTPUT FACES
# Modes: ok, fail (exit 3), crash (SIGSEGV), hang, ignore-term, fork (leaves a child running that
# ignores SIGTERM), garbage, empty, no-output, flood (megabytes on stdout and stderr, then ok),
# nan (a vertex with NaN coordinates).
mode=$1 input=$2 output=$3 faces=$4

write_tetrahedron() {
  printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$output"
}

case "$mode" in
  ok) write_tetrahedron ;;
  fail) echo "fake: something went wrong" >&2; exit 3 ;;
  crash) echo "fake: about to crash" >&2; kill -SEGV $$ ;;
  hang) sleep 1000 ;;
  ignore-term) trap '' TERM; echo "fake: ignoring SIGTERM" >&2; sleep 1000 ;;
  fork) (trap '' TERM; exec sleep 1000) & write_tetrahedron ;;
  garbage) printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1 two 3\n' > "$output" ;;
  empty) : > "$output" ;;
  no-output) echo "fake: done (but wrote nothing)" ;;
  flood)
    head -c 20000000 /dev/zero | tr '\0' 'e' >&2
    head -c 20000000 /dev/zero | tr '\0' 'o'
    echo >&2; echo "fake: flood finished" >&2
    write_tetrahedron ;;
  nan) printf 'OFF\n4 4 0\nnan 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$output" ;;
  *) echo "fake: unknown mode $mode" >&2; exit 2 ;;
esac
