#!/usr/bin/python3
"""Runs `meshdev info` on every case of the corpus and checks exit code and message.

Usage: run_bad_inputs.py MESHDEV_BINARY OUT_DIR

Generates the corpus into OUT_DIR (make_bad_inputs.py), then runs each case with a 10 s timeout
and a 1 GiB address-space limit. Under AddressSanitizer (MESHDEV_SANITIZED=1, set by
scripts/sanitize.sh) RLIMIT_AS cannot be used, because ASan reserves terabytes of virtual
address space; the same 1 GiB bound is then enforced by ASan itself (max_allocation_size_mb,
hard_rss_limit_mb), which turns a bigger allocation into a reported failure. A case passes when the exit code is the expected one, the
process was not killed by a signal or the timeout, and (for errors) stderr names the file and
contains the expected substring (for valid files, stdout contains it). Prints one line per
failure and a final "N passed, M failed"; exits 1 if any failed.
"""
import os
import resource
import subprocess
import sys

TIMEOUT_S = 10
ADDRESS_SPACE = 1 << 30


SANITIZED = os.environ.get("MESHDEV_SANITIZED") == "1"


def limit():
    if not SANITIZED:
        resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE, ADDRESS_SPACE))


def child_env():
    env = dict(os.environ)
    if SANITIZED:
        mb = ADDRESS_SPACE >> 20
        extra = "max_allocation_size_mb=%d:hard_rss_limit_mb=%d:allocator_may_return_null=0" % (mb, mb)
        env["ASAN_OPTIONS"] = (env.get("ASAN_OPTIONS", "") + ":" + extra).lstrip(":")
    return env


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: run_bad_inputs.py MESHDEV_BINARY OUT_DIR")
    binary, out = sys.argv[1], sys.argv[2]
    here = os.path.dirname(os.path.abspath(__file__))
    subprocess.run([sys.executable, os.path.join(here, "make_bad_inputs.py"), out], check=True,
                   stdout=subprocess.DEVNULL)
    passed = failed = 0
    crashes = hangs = uncaught = false_success = 0
    with open(os.path.join(out, "cases.tsv"), encoding="utf-8") as manifest:
        rows = [line.rstrip("\n").split("\t") for line in manifest][1:]
    for name, code, expect, what in rows:
        path = os.path.join(out, name)
        problem = None
        try:
            r = subprocess.run([binary, "info", path], capture_output=True, timeout=TIMEOUT_S,
                               preexec_fn=limit, env=child_env(), stdin=subprocess.DEVNULL)
            stderr = r.stderr.decode("utf-8", "replace")
            stdout = r.stdout.decode("utf-8", "replace")
            if r.returncode < 0:
                crashes += 1
                problem = "killed by signal %d" % -r.returncode
            elif r.returncode == 70 or "Sanitizer" in stderr:
                uncaught += 1
                problem = "uncaught exception or sanitizer report (exit %d): %s" % (
                    r.returncode, stderr.strip()[-600:])
            elif r.returncode == 0 and int(code) != 0:
                false_success += 1
                problem = "exit 0 on invalid input"
            elif r.returncode != int(code):
                problem = "exit %d, expected %s; stderr: %s" % (r.returncode, code, stderr.strip()[:300])
            elif int(code) != 0 and name not in stderr:
                problem = "stderr does not name the file: %s" % stderr.strip()[:300]
            elif int(code) != 0 and expect not in stderr:
                problem = "stderr lacks %r: %s" % (expect, stderr.strip()[:300])
            elif int(code) == 0 and expect not in stdout:
                problem = "stdout lacks %r: %s" % (expect, stdout.strip()[:300])
        except subprocess.TimeoutExpired:
            hangs += 1
            problem = "timeout after %d s" % TIMEOUT_S
        if problem:
            failed += 1
            print("FAIL %s (%s): %s" % (name, what, problem))
        else:
            passed += 1
    print("%d cases: %d crashes, %d hangs, %d uncaught exceptions or sanitizer reports, "
          "%d exit-0 on invalid input" % (len(rows), crashes, hangs, uncaught, false_success))
    print("%d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
