#!/usr/bin/env python3
"""Determinism of `meshdev compare`: the same inputs, seed and sampling give byte-identical
outputs with 1 and 2 threads and across repeated runs.

Usage: determinism_test.py MESHDEV_BINARY SCRATCH_DIR
The meshes are built here and written as OFF and ascii PLY (with colours), so nothing outside the
repository is needed. For each mesh pair and each sampling/seed, four runs (1 thread, 2 threads,
each twice) write --json, --csv, --samples and --colored; the JSON is compared after removing its
timing fields ("seconds" blocks) and options.threads, the other files byte for byte. Different
Monte Carlo seeds must give different samples (the seed is really used).
Prints one line per check and a final "N passed, M failed" line.
"""
import math
import os
import re
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


def path(name):
    return os.path.join(scratch, name)


def write_off(name, verts, faces):
    with open(path(name), "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(verts), len(faces)))
        f.writelines("%r %r %r\n" % v for v in verts)
        f.writelines("%d %s\n" % (len(t), " ".join(map(str, t))) for t in faces)
    return path(name)


def write_ply(name, verts, colors, faces):
    with open(path(name), "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\n" % len(verts))
        f.write("property double x\nproperty double y\nproperty double z\n")
        f.write("property uchar red\nproperty uchar green\nproperty uchar blue\n")
        f.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n" % len(faces))
        for v, c in zip(verts, colors):
            f.write("%r %r %r %d %d %d\n" % (*v, *c))
        f.writelines("3 %d %d %d\n" % t for t in faces)
    return path(name)


def bumpy_grid(n, size, phase):
    """An n x n grid of quads with a height field: polygons, so the reader triangulates."""
    verts = [(i * size / n, j * size / n, 0.1 * math.sin(3 * i / n + phase) * math.cos(2 * j / n))
             for j in range(n + 1) for i in range(n + 1)]
    quads = [(j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i)
             for j in range(n) for i in range(n)]
    return verts, quads


def sphere(levels, scale, color_shift):
    """An octahedron subdivided `levels` times, projected on a sphere, with vertex colours."""
    verts = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    for _ in range(levels):
        mid, out = {}, []

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                p = [(x + y) / 2 for x, y in zip(verts[a], verts[b])]
                r = math.sqrt(sum(c * c for c in p))
                verts.append(tuple(c / r for c in p))
                mid[key] = len(verts) - 1
            return mid[key]

        for a, b, c in faces:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        faces = out
    verts = [tuple(scale * c for c in v) for v in verts]
    colors = [(int(127 + 120 * v[0] / scale), (37 * i + color_shift) % 256, 200) for i, v in enumerate(verts)]
    return verts, colors, faces


# Mesh pairs: offset height fields (polygons), coloured spheres of different resolution, and a
# cube against a copy with degenerate and duplicate faces (ties between equidistant faces).
ga, gb = bumpy_grid(12, 1.0, 0.0), bumpy_grid(7, 1.0, 0.4)
sa, sb = sphere(3, 1.0, 0), sphere(2, 1.02, 90)
cube_v = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
cube_f = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
pairs = [
    ("grids", write_off("grid_a.off", *ga), write_off("grid_b.off", *gb)),
    ("spheres", write_ply("sphere_a.ply", *sa), write_ply("sphere_b.ply", *sb)),
    ("cubes", write_off("cube_a.off", cube_v, cube_f),
     write_off("cube_b.off", cube_v + [(0.5, 0.5, 0.5)], cube_f + [(0, 1, 3, 2), (0, 8, 7), (8, 8, 1)])),
]
configs = [
    ("vertices-faces", ["--sampling", "vertices,faces"]),
    ("edges", ["--sampling", "vertices,edges,faces", "--step", "2%"]),
    ("montecarlo-1", ["--sampling", "montecarlo", "--seed", "1"]),
    ("montecarlo-7", ["--sampling", "montecarlo", "--seed", "7", "--sample-count", "3000"]),
    ("montecarlo-grid", ["--sampling", "montecarlo,vertices", "--seed", "12345", "--index", "grid"]),
]

TIMING = [re.compile(rb'\n\s*"seconds": \{[^{}]*\},?'), re.compile(rb'\n\s*"seconds": [-+0-9.eE]+,?'),
          re.compile(rb'\n\s*"threads": [0-9]+,?')]


def without_timing(data):
    for pattern in TIMING:
        data = pattern.sub(b"", data)
    return data


def run_once(a, b, args, threads, tag):
    outputs = {"json": path(tag + ".json"), "csv": path(tag + ".csv"), "samples": path(tag + "_s.csv"),
               "colored": path(tag + "_c.ply")}
    cmd = [meshdev, "compare", a, b, "--threads", str(threads), "-q", *args]
    for key, file in outputs.items():
        cmd += ["--" + key, file]
    p = subprocess.run(cmd, capture_output=True, timeout=300, stdin=subprocess.DEVNULL)
    if p.returncode != 0:
        return None, p.stderr.decode(errors="replace")
    result = {}
    for key, file in outputs.items():
        with open(file, "rb") as f:
            result[key] = without_timing(f.read()) if key == "json" else f.read()
    return result, ""


samples_by_seed = {}
for pair, a, b in pairs:
    for name, args in configs:
        runs = []
        for threads in (1, 2):
            for repeat in (1, 2):
                out, err = run_once(a, b, args, threads, f"{pair}_{name}_t{threads}_r{repeat}")
                check(f"{pair} {name} threads={threads} run {repeat} exits 0", out is not None, err)
                if out is not None:
                    runs.append((threads, repeat, out))
        for threads, repeat, out in runs[1:]:
            for key in out:
                check(f"{pair} {name}: {key} of threads={threads} run {repeat} == threads=1 run 1",
                      out[key] == runs[0][2][key])
        if runs and name.startswith("montecarlo"):
            samples_by_seed[(pair, name)] = runs[0][2]["samples"]
    seeds = [samples_by_seed.get((pair, n)) for n in ("montecarlo-1", "montecarlo-7")]
    check(f"{pair}: Monte Carlo seeds 1 and 7 give different samples",
          None not in seeds and seeds[0] != seeds[1])

print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
