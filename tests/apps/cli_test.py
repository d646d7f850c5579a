#!/usr/bin/env python3
"""End-to-end checks of the meshdev command line: exit codes, messages, outputs.

Usage: cli_test.py MESHDEV_BINARY SCRATCH_DIR
Meshes are written here as small OFF/PLY files, so nothing outside the repository is needed.
Prints one line per check and a final "N passed, M failed" line.
"""
import csv
import json
import os
import shutil
import subprocess
import sys

meshdev, scratch = sys.argv[1], sys.argv[2]
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
passed, failed = 0, 0


def check(name, condition, detail=""):
    global passed, failed
    if condition:
        passed += 1
        print(f"ok    {name}")
    else:
        failed += 1
        print(f"FAIL  {name} {detail}")


def run(*args, timeout=60):
    p = subprocess.run([meshdev, *args], capture_output=True, text=True, timeout=timeout,
                       stdin=subprocess.DEVNULL)
    return p.returncode, p.stdout, p.stderr


def path(name):
    return os.path.join(scratch, name)


def write(name, text):
    with open(path(name), "w") as f:
        f.write(text)
    return path(name)


def grid_off(name, n, z):
    """An n x n grid of quads over the unit square at height z, as OFF polygons."""
    verts = [f"{i / n} {j / n} {z}" for j in range(n + 1) for i in range(n + 1)]
    quads = [f"4 {j*(n+1)+i} {j*(n+1)+i+1} {(j+1)*(n+1)+i+1} {(j+1)*(n+1)+i}"
             for j in range(n) for i in range(n)]
    return write(name, "OFF\n%d %d 0\n%s\n%s\n" % (len(verts), len(quads), "\n".join(verts),
                                                 "\n".join(quads)))


a = grid_off("a.off", 6, 0.0)
b = grid_off("b.off", 4, 0.25)

# 1. A normal comparison: exit 0, Table-1 block, JSON/CSV/samples/coloured outputs.
code, out, err = run("compare", a, b, "--json", path("r.json"), "--csv", path("r.csv"),
                     "--samples", path("s.csv"), "--colored", path("c.ply"))
check("compare exits 0", code == 0, err)
check("report has the Table-1 rows", "vertices" in out and "faces" in out and "area" in out)
report = json.load(open(path("r.json")))
check("json schema", report.get("schema") == "meshdev.compare/1")
g = report["directions"]["forward"]["stats"]["geometry"]
check("offset planes: forward geometry is 0.25 everywhere",
      abs(g["min"] - 0.25) < 1e-12 and abs(g["max"] - 0.25) < 1e-12, g)
check("symmetric hausdorff", abs(report["symmetric"]["geometry"]["hausdorff"] - 0.25) < 1e-12)
rows = list(csv.DictReader(open(path("s.csv"))))
total = report["directions"]["forward"]["samples"] + report["directions"]["backward"]["samples"]
check("one samples row per sample", len(rows) == total, f"{len(rows)} vs {total}")
summary = list(csv.DictReader(open(path("r.csv"))))
check("summary csv has forward, backward, symmetric rows",
      {r["direction"] for r in summary} == {"forward", "backward", "symmetric"})
code, out, err = run("info", path("c.ply"))
check("coloured PLY reads back with color and quality",
      code == 0 and "color" in out and "quality" in out, out + err)

# 2. Identical meshes: exactly 0.
code, out, err = run("compare", a, a, "--json", path("same.json"), "--sampling",
                     "vertices,edges,faces", "-q")
same = json.load(open(path("same.json")))
check("identical meshes give exactly 0",
      code == 0 and all(s["max"] == 0.0 for d in same["directions"].values()
                        for s in d["stats"].values()))

# 3. Determinism: 1 thread and 2 threads give byte-identical reports (timings removed).
def stripped(p):
    j = json.load(open(p))
    j.pop("seconds")
    for d in j["directions"].values():
        d.pop("seconds")
    j["options"].pop("threads")
    return j


run("compare", a, b, "--sampling", "montecarlo", "--threads", "1", "--json", path("t1.json"), "-q")
run("compare", a, b, "--sampling", "montecarlo", "--threads", "2", "--json", path("t2.json"), "-q")
check("1 thread == 2 threads", stripped(path("t1.json")) == stripped(path("t2.json")))

# 4. Exit codes and messages.
code, out, err = run("compare", path("missing.off"), b)
check("missing file: exit 3 naming the file", code == 3 and "missing.off" in err, f"{code} {err}")
bad = write("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")
code, out, err = run("compare", bad, b)
check("out-of-range index: exit 3 naming the file", code == 3 and "bad.off" in err, f"{code} {err}")
code, out, err = run("compare", a, b, "--attributes", "color")
check("attribute missing on both: exit 4", code == 4 and "color" in err, f"{code} {err}")
code, out, err = run("compare", a, b, "--no-such-option")
check("unknown option: exit 2", code == 2, f"{code} {err}")
code, out, err = run("compare", a, b, "--step", "-1")
check("negative step: exit 2", code == 2, f"{code} {err}")
# A colour range that is reversed or not finite coloured everything one colour without a word.
code, out, err = run("compare", a, b, "--range", "1", "0", "--colored", path("range.ply"))
check("reversed --range: exit 4 naming the range", code == 4 and "colour range" in err, f"{code} {err}")
# --ratio nan passed CLI11's range check and was then read as "no --ratio".
code, out, err = run("simplify", a, path("s.ply"), "--method", "openmesh-quadric", "--ratio", "nan")
check("simplify --ratio nan: exit 2 naming --ratio", code == 2 and "--ratio must be" in err,
      f"{code} {err}")
# 100,000 OpenMP threads crashed the process (SIGSEGV) before --threads had an upper bound.
code, out, err = run("compare", a, b, "--threads", "100000")
check("--threads above 1024: exit 2 naming the range", code == 2 and "1024" in err, f"{code} {err}")
# Sample counts that cannot be held: edge samples at a step far too small were made until
# memory ran out, and a Monte Carlo count beyond 2^31 was allocated (both "out of memory", exit
# 70). A count within 2^31 whose results exceed the memory available: Compare.ASampleCount...
code, out, err = run("compare", a, b, "--sampling", "edges", "--step", "1e-12")
check("edge step far too small: exit 4 naming the step", code == 4 and "1e-12 would" in err,
      f"{code} {err}")
code, out, err = run("compare", a, b, "--sampling", "montecarlo", "--sample-count", "4294967296")
check("--sample-count beyond 2^31: exit 4 naming the limit",
      code == 4 and "more than the 2^31" in err, f"{code} {err}")
cloud = write("cloud.off", "OFF\n2 0 0\n0.5 0.5 1\n0.2 0.2 2\n")
code, out, err = run("compare", a, cloud)
check("point cloud as B: exit 4 explaining why", code == 4 and "no faces" in err, f"{code} {err}")
code, out, err = run("compare", cloud, a, "--direction", "forward", "--sampling", "vertices")
check("point cloud as A, forward: exit 0", code == 0, err)

# 5. Writes are checked and atomic: a full disk fails with exit 5 and leaves earlier output.
code, out, err = run("compare", a, b, "--json", "/dev/full", "-q")
check("json to a full disk: exit 5", code == 5 and "/dev/full" in err, f"{code} {err}")
before = open(path("r.json")).read()
code, out, err = run("compare", a, b, "--json", path("no/such/dir/r.json"), "-q")
check("json into a missing folder: exit 5", code == 5, f"{code} {err}")
check("earlier output intact", open(path("r.json")).read() == before)
# Output paths are checked before the work (a long comparison was computed, then lost to a
# mistyped folder under -q): the message names the folder and no time is reported.
code, out, err = run("compare", a, b, "--json", path("no/such/dir/r.json"))
check("missing output folder: refused before the comparison",
      code == 5 and "cannot write in folder" in err and "time:" not in out, f"{code} {out} {err}")
for command in (["simplify", a, path("no/such/dir/s.ply"), "--method", "openmesh-quadric",
                 "--ratio", "0.5"],
                ["render", a, "-o", path("no/such/dir/r.png")]):
    code, out, err = run(*command)
    check(f"{command[0]} into a missing folder: exit 5 naming the folder",
          code == 5 and "cannot write in folder" in err, f"{code} {err}")
code, out, err = run("compare", a, b, "--atlas", path("new/atlas/folder"), "-q")
check("--atlas makes its folder", code == 0 and os.path.isdir(path("new/atlas/folder")) and
      any(f.endswith("_atlas.png") for f in os.listdir(path("new/atlas/folder"))), f"{code} {err}")

code, out, err = run("--help")
check("--help exits 0", code == 0 and "compare" in out)
code, out, err = run("compare", "--help")
check("compare --help lists examples and exit codes", code == 0 and "Exit codes" in out)

print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
