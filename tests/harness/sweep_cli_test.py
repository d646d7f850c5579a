#!/usr/bin/python3
"""End-to-end tests of `meshdev sweep / guard / merge / plot` on meshes built in code.

usage: sweep_cli_test.py MESHDEV MAKE_MESHES SCRATCH

1. An uninterrupted sweep (the reference).
2. The same sweep killed with SIGKILL 20 times at random (seeded) moments: alternately from a
   run's start and once it has written a line; resumed each time, then run to completion: the CSV
   must equal the reference except for the timing columns, with no row missing or duplicated.
   A sweep that completes before 20 kills is checked and the kills go on in a new directory.
3. guard: identical CSVs exit 0; a degraded value, a missing row and a failed status exit 1
   with a table.
4. --shard I/3 three times + merge equals the single run.
5. plot: PNG/SVG/PDF files are written (matplotlib).
"""
import csv
import os
import random
import shutil
import signal
import subprocess
import sys
import time

meshdev, make_meshes, scratch = sys.argv[1:4]
TIMING = {"simplify_seconds", "metric_seconds"}
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def run(args, **kw):
    return subprocess.run([meshdev] + args, capture_output=True, text=True, **kw)


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def comparable(path):
    return sorted(tuple((k, v) for k, v in r.items() if k not in TIMING) for r in rows(path))


shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
subprocess.run([make_meshes, scratch], check=True)
config = os.path.join(scratch, "sweep.json")
with open(config, "w") as f:
    f.write('{"meshes": ["icosphere3.ply", "grid12.ply"], '
            '"simplifiers": ["openmesh-quadric", "openmesh-hausdorff", "meshopt"], '
            '"ratios": [50, 75, 90], "sample_count": 20000, "plots": false}\n')

# 1. Reference run.
ref = os.path.join(scratch, "ref")
t0 = time.monotonic()
p = run(["sweep", config, "--out", ref, "--no-progress"])
duration = time.monotonic() - t0
check(p.returncode == 0, "reference sweep exits 0 (%s)" % p.stderr.strip()[-300:])
ref_rows = comparable(os.path.join(ref, "sweep.csv"))
jobs = {r["job_key"] for r in rows(os.path.join(ref, "sweep.csv"))}
check(len(jobs) == 2 * 3 * 3, "reference has 18 jobs (got %d)" % len(jobs))
check("sweep: [18/18]" in p.stderr, "plain log lines when stderr is not a terminal")

# 2. Killed 20 times at random moments, resumed each time.
def lines_on_disk(path):
    try:
        with open(path, "rb") as f:
            return f.read().count(b"\n")
    except OSError:
        return 0


rng = random.Random(20240611)
job_time = duration / max(len(jobs), 1)
# Two kinds of run, alternating: one killed at a random moment of its first two mean job times
# from its start (startup, locking, reading the CSV, a simplification or a comparison: often before
# it writes anything), one killed once it has written a line, within half a mean job time (a torn
# tail or the next job). The second kind makes progress; the first kills at any moment whatever
# the machine's speed. A sweep that finishes by itself ends an episode: it is resumed, checked
# against the reference, and the next episode starts from an empty directory, until 20 runs have
# been killed. So the number of kills does not depend on how fast this machine runs the sweep
# compared with the reference run (CI finished a single sweep in 9 kills twice).
kills = runs = 0
episodes = []  # (directory, kills in it)
while kills < 20 and runs < 100:
    out = os.path.join(scratch, "killed%d" % len(episodes))
    out_csv = os.path.join(out, "sweep.csv")
    episode_kills = 0
    while kills < 20 and runs < 100:
        before = lines_on_disk(out_csv)
        proc = subprocess.Popen([meshdev, "sweep", config, "--out", out, "--no-progress", "-q"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if runs % 2 == 0:
            time.sleep(rng.uniform(0.0, 2 * job_time))
        else:
            deadline = time.monotonic() + 30 * max(duration, 1.0)
            while (proc.poll() is None and lines_on_disk(out_csv) == before and
                   time.monotonic() < deadline):
                time.sleep(0.002)
            time.sleep(rng.uniform(0.0, job_time / 2))
        runs += 1
        if proc.poll() is None:
            proc.send_signal(signal.SIGKILL)
            kills += 1
            episode_kills += 1
        proc.wait()
        if proc.returncode == 0:
            break  # a run that finished by itself: nothing is left to kill
    episodes.append((out, episode_kills))

for i, (out, episode_kills) in enumerate(episodes):
    out_csv = os.path.join(out, "sweep.csv")
    partial = rows(out_csv) if os.path.exists(out_csv) else []
    print("episode %d: %d kills, %d complete rows of %d on disk" %
          (i, episode_kills, len(partial), len(ref_rows)))
    p = run(["sweep", config, "--out", out, "--no-progress"])
    check(p.returncode == 0, "episode %d: resumed sweep exits 0 after %d kills" % (i, episode_kills))
    got = rows(out_csv)
    keys = [(r["job_key"], r["measure_index"]) for r in got]
    check(len(keys) == len(set(keys)), "episode %d: no duplicated row after the kills" % i)
    check(comparable(out_csv) == ref_rows,
          "episode %d: resumed CSV equals the uninterrupted one except timings (%d rows)" %
          (i, len(got)))
    p = run(["sweep", config, "--out", out, "--no-progress"])
    check("0 jobs computed" in p.stderr, "episode %d: a complete sweep re-run computes nothing" % i)
check(kills == 20, "20 runs were killed mid-sweep (%d kills in %d runs, %d episodes)" %
      (kills, runs, len(episodes)))

# 3. guard.
base = os.path.join(ref, "sweep.csv")
p = run(["guard", "--baseline", base, "--current", base])
check(p.returncode == 0 and "PASS" in p.stdout, "guard: identical CSVs exit 0")
all_rows = rows(base)
fields = list(all_rows[0].keys())


def write_variant(name, change):
    data = [dict(r) for r in all_rows]
    data = change(data)
    path = os.path.join(scratch, name + ".csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
        w.writeheader()
        w.writerows(data)
    return path


def degrade(data):
    for r in data:
        if r["measure"] == "geometry" and r["simplifier"] == "meshopt" and r["reduction_percent"] == "90":
            r["symmetric_mean"] = repr(float(r["symmetric_mean"]) * 1.5)
    return data


p = run(["guard", "--baseline", base, "--current", write_variant("degraded", degrade)])
check(p.returncode == 1 and "worse" in p.stdout and "+50.0%" in p.stdout,
      "guard: a value 50 % worse exits 1 with a table")
print(p.stdout)
p = run(["guard", "--baseline", base, "--current", write_variant("missing", lambda d: d[1:])])
check(p.returncode == 1 and "missing" in p.stdout, "guard: a missing row exits 1")


def fail_one(data):
    victim = data[0]["job_key"]
    kept = [r for r in data if r["job_key"] != victim]
    failed = dict(data[0])
    for k in fields:
        if k.startswith(("forward_", "backward_", "symmetric_", "hausdorff")):
            failed[k] = ""
    failed.update(status="failed", message="backend crashed", measure="", measure_index="0",
                  measure_count="1")
    return kept + [failed]


p = run(["guard", "--baseline", base, "--current", write_variant("failed", fail_one)])
check(p.returncode == 1 and "failed" in p.stdout, "guard: a failed status exits 1")
p = run(["guard", "--baseline", base, "--current", write_variant("degraded2", degrade),
         "--tolerance", "60%"])
check(p.returncode == 0, "guard: --tolerance 60% accepts +50 %")
p = run(["guard", "--baseline", base, "--current", base, "--metrics", "nonsense"])
check(p.returncode == 4, "guard: an unknown metric exits 4")
# What would let every run pass exits 4: a NaN tolerance, a measure of no row, an empty baseline.
p = run(["guard", "--baseline", base, "--current", base, "--absolute-tolerance", "nan"])
check(p.returncode == 4 and "tolerances" in p.stderr, "guard: a NaN tolerance exits 4")
p = run(["guard", "--baseline", base, "--current", base, "--measures", "geomtry"])
check(p.returncode == 4 and "geomtry" in p.stderr, "guard: a measure of no row exits 4")
p = run(["guard", "--baseline", os.devnull, "--current", base])
check(p.returncode == 4 and "nothing to guard" in p.stderr, "guard: an empty baseline exits 4")

# 4. Shards + merge.
parts = []
for i in range(3):
    d = os.path.join(scratch, "shard%d" % i)
    p = run(["sweep", config, "--out", d, "--shard", "%d/3" % i, "--no-progress", "-q"])
    check(p.returncode == 0, "shard %d/3 exits 0" % i)
    parts.append(os.path.join(d, "sweep.csv"))
merged = os.path.join(scratch, "merged.csv")
p = run(["merge", "-o", merged] + parts)
check(p.returncode == 0, "merge exits 0")
check(comparable(merged) == ref_rows, "shards 0..2/3 merged equal the single run")
p = run(["sweep", config, "--shard", "3/3"])
check(p.returncode == 4, "--shard 3/3 is refused (exit 4)")

# 5. Plots.
p = run(["plot", base, "--out", os.path.join(scratch, "plots")])
made = sorted(os.listdir(os.path.join(scratch, "plots"))) if p.returncode == 0 else []
check(p.returncode == 0 and "icosphere3_fig8.png" in made and "icosphere3_geometry.svg" in made
      and "grid12_normal.pdf" in made, "plot writes PNG/SVG/PDF (%s)" % p.stderr.strip()[-200:])
# Three mistakes that were Python tracebacks (exit 70), the last two after the figures' work.
binary = os.path.join(scratch, "binary.csv")
with open(binary, "wb") as f:
    f.write(bytes([0xB3, 0x00, 0xFF]) * 1000)
p = run(["plot", binary, "--out", os.path.join(scratch, "plots_binary")])
check(p.returncode == 3 and "not UTF-8" in p.stderr, "plot of a binary file: exit 3 (%s)"
      % p.stderr.strip()[-200:])
p = run(["plot", base, "--out", os.path.join(scratch, "plots_gif"), "--formats", "png,gif"])
check(p.returncode == 2 and "gif not supported" in p.stderr
      and not os.path.exists(os.path.join(scratch, "plots_gif")),
      "plot --formats gif: exit 2 before any figure (%s)" % p.stderr.strip()[-200:])
p = run(["plot", base, "--out", os.path.join(base, "plots")])  # a folder under a file
check(p.returncode == 5 and "cannot create the folder" in p.stderr,
      "plot into a folder under a file: exit 5 (%s)" % p.stderr.strip()[-200:])

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
