#!/usr/bin/env python3
"""Measure every available simplifier backend on real meshes with meshdev's own metric.

usage: measure_backends.py MESHDEV WORKDIR [--meshes bunny00 armadillo] [--ratios 0.5 0.9 0.99]
                           [--backends a,b,...]

For each mesh (from Debian's /usr/share/doc/libcgal-demo/data.tar.gz, data/meshes/NAME.off),
backend (every one `meshdev simplify --list` reports available, except `external`) and
reduction ratio it runs

    meshdev simplify MESH.off OUT.ply --method BACKEND --ratio R
    meshdev compare MESH.off OUT.ply --json r.json

and reads the backend's wall time and faces from the first command and symmetric.geometry.mean,
symmetric.geometry.hausdorff and symmetric.normal_angle.mean from r.json. Prints one Markdown
table per mesh and writes WORKDIR/measurements.csv. Runs sequentially (one job at a time).
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tarfile

DATA = "/usr/share/doc/libcgal-demo/data.tar.gz"


def extract(name, workdir):
    path = os.path.join(workdir, name + ".off")
    if not os.path.exists(path):
        with tarfile.open(DATA) as tar:
            member = tar.getmember("data/meshes/%s.off" % name)
            with tar.extractfile(member) as src, open(path, "wb") as dst:
                dst.write(src.read())
    return path


def available_backends(meshdev):
    out = subprocess.run([meshdev, "simplify", "--list"], capture_output=True, text=True).stdout
    names = re.findall(r"^(\S+)\s+available$", out, flags=re.M)
    return [n for n in names if n != "external"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("meshdev")
    ap.add_argument("workdir")
    ap.add_argument("--meshes", nargs="+", default=["bunny00", "armadillo"])
    ap.add_argument("--ratios", nargs="+", type=float, default=[0.5, 0.9, 0.99])
    ap.add_argument("--backends", default="")
    a = ap.parse_args()
    os.makedirs(a.workdir, exist_ok=True)
    backends = a.backends.split(",") if a.backends else available_backends(a.meshdev)
    rows = []
    for mesh in a.meshes:
        src = extract(mesh, a.workdir)
        for backend in backends:
            for ratio in a.ratios:
                out = os.path.join(a.workdir, "%s_%s_%g.ply" % (mesh, backend, ratio))
                js = out[:-4] + ".json"
                row = {"mesh": mesh, "backend": backend, "ratio": ratio}
                s = subprocess.run([a.meshdev, "simplify", src, out, "--method", backend,
                                    "--ratio", str(ratio)], capture_output=True, text=True)
                m = re.search(r"(\d+) -> (\d+) faces \(target (\d+)\) in ([0-9.eE+-]+) s, (\S+)",
                              s.stdout)
                if s.returncode != 0 or not m:
                    row["status"] = "failed: " + (s.stderr.strip().splitlines() or ["?"])[-1]
                    rows.append(row)
                    print(row, file=sys.stderr)
                    continue
                row.update(input=int(m.group(1)), faces=int(m.group(2)), target=int(m.group(3)),
                           seconds=float(m.group(4)), status=m.group(5))
                c = subprocess.run([a.meshdev, "compare", src, out, "--json", js],
                                   capture_output=True, text=True)
                if c.returncode not in (0,) or not os.path.exists(js):
                    row["status"] += " (compare failed: %s)" % c.stderr.strip()[-200:]
                else:
                    sym = json.load(open(js))["symmetric"]
                    row.update(geometry_mean=sym["geometry"]["mean"],
                               geometry_hausdorff=sym["geometry"]["hausdorff"],
                               normal_angle_mean=sym["normal_angle"]["mean"],
                               geometry_mean_rel=sym["geometry"]["relative"]["mean"])
                rows.append(row)
                print("%s %s %g: %s" % (mesh, backend, ratio, row), file=sys.stderr)
    keys = ["mesh", "backend", "ratio", "input", "target", "faces", "status", "seconds",
            "geometry_mean", "geometry_hausdorff", "normal_angle_mean", "geometry_mean_rel"]
    with open(os.path.join(a.workdir, "measurements.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in keys})
    for mesh in a.meshes:
        print("\n**%s**\n" % mesh)
        head = "| backend |" + "".join(" %g %%: time / faces | geom. mean / Hausdorff | normal ° |" % (100 * r) for r in a.ratios)
        print(head)
        print("| --- |" + " --- | --- | --- |" * len(a.ratios))
        for backend in backends:
            cells = []
            for ratio in a.ratios:
                r = next((x for x in rows if x["mesh"] == mesh and x["backend"] == backend
                          and x["ratio"] == ratio), None)
                if r is None or "faces" not in r:
                    cells += [r["status"] if r else "-", "", ""]
                    continue
                mark = "" if r["status"] == "ok" else " (%s)" % r["status"]
                cells.append("%.2f s / %d%s" % (r["seconds"], r["faces"], mark))
                if "geometry_mean" in r:
                    cells.append("%.3g / %.3g" % (r["geometry_mean"], r["geometry_hausdorff"]))
                    cells.append("%.2f" % r["normal_angle_mean"])
                else:
                    cells += ["?", "?"]
            print("| `%s` | %s |" % (backend, " | ".join(cells)))


if __name__ == "__main__":
    main()
