#!/usr/bin/python3
"""Cross-check of meshdev's one-sided distances against MeshLab's "Hausdorff Distance" filter.

Usage: meshlab_hausdorff.py MESHDEV_BINARY SCRATCH_DIR

For each pair of real meshes (A, B) and each direction (A->B, B->A) both tools sample the
vertices of the sampled mesh only and find the closest point on the other mesh's surface:

  * MeshLab: `xvfb-run -a meshlabserver -i A.ply -i B.ply -s hausdorff.mlx` with SampleVert only,
    SampleNum >= the vertex count (then vcglib's VertexUniform takes every vertex) and MaxDist far
    above the bbox diagonal (samples farther than MaxDist are dropped from MeshLab's statistics);
  * meshdev: `meshdev compare A B --sampling vertices --direction forward --json out.json -q`.

The forward min / max / mean / RMS and the sample counts are compared. A row (pair, direction)
passes when the counts are equal and every statistic agrees to 1e-5 relative, or, for values
near zero, to FLOAT_NOISE = 2e-8 x bbox diagonal absolute. That floor is MeshLab's float32
arithmetic noise: with coordinates up to 5e3 (float spacing 4.9e-4) its distances differ from the
exact double-precision ones by up to 1.07e-8 x diagonal (measured, docs/validation.md; meshdev's
values at those samples were confirmed by a double-precision brute force). Rows that pass only
thanks to the floor, i.e. that would fail the stricter rule "1e-5 relative; min: 1e-9 x diagonal
absolute", are marked "ok*" and counted on a separate line.

Both tools read the SAME files, written by this script (binary PLY, float32 coordinates):
  * every mesh of a pair is moved by the same transform (A's bbox centre to the origin, A's bbox
    diagonal scaled to 1e4) and rounded to float32. MeshLab stores coordinates as float, meshdev
    reads the float values exactly, so there is no input rounding difference. The scale makes
    MeshLab's log (printf "%f", 6 decimals) precise enough for a 1e-5 relative comparison;
  * unreferenced vertices are removed (faces re-indexed). MeshLab samples EVERY vertex of the
    sampled mesh, meshdev only the referenced ones (docs/validation.md); without this step the
    counts and statistics differ by definition.
Polygons are fan-triangulated (all meshes used here are triangle meshes); STL corners are welded
when their coordinates are exactly equal (as meshdev's STL reader does).

Exit status: 0 all rows pass, 1 a row failed (or a tool failed), 77 meshlabserver or xvfb-run is
not installed (skip). Prints a table and, last, exactly "N passed, M failed".
"""

import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tarfile

SKIP = 77
TARGET_DIAGONAL = 1.0e4
REL_TOL = 1e-5
STRICT_MIN_ABS_TOL = 1e-9  # x bbox diagonal (A's, after scaling): the strict rule for min
FLOAT_NOISE = 2e-8  # x bbox diagonal: absolute floor for every statistic (MeshLab float32 noise)
CGAL_ARCHIVE = "/usr/share/doc/libcgal-demo/data.tar.gz"
HERE = os.path.dirname(os.path.abspath(__file__))
SHARED_DATA = os.environ.get(
    "MESHDEV_SHARED_DATA", os.path.normpath(os.path.join(HERE, "..", "..", "..", "shared", "data")))


# ---------------------------------------------------------------------------------------------
# Minimal readers (positions and triangles only)

def read_off(path):
    with open(path, "r", encoding="ascii", errors="replace") as f:
        tokens = []
        for line in f:
            line = line.split("#", 1)[0]
            tokens.extend(line.split())
    if not tokens or not tokens[0].endswith("OFF"):
        raise ValueError("%s: not an OFF file" % path)
    if tokens[0] != "OFF":
        raise ValueError("%s: only plain OFF is supported here" % path)
    nv, nf = int(tokens[1]), int(tokens[2])
    i = 4
    verts = []
    for _ in range(nv):
        verts.append((float(tokens[i]), float(tokens[i + 1]), float(tokens[i + 2])))
        i += 3
    faces = []
    for _ in range(nf):
        n = int(tokens[i])
        idx = [int(t) for t in tokens[i + 1:i + 1 + n]]
        i += 1 + n
        for k in range(1, n - 1):
            faces.append((idx[0], idx[k], idx[k + 1]))
    return verts, faces


PLY_TYPES = {
    "char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h",
    "ushort": "H", "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I",
    "float": "f", "float32": "f", "double": "d", "float64": "d",
}


def read_ply(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise ValueError("%s: not a PLY file" % path)
    body = data.index(b"\n", end) + 1
    header = data[:body].decode("ascii", errors="replace").splitlines()
    fmt = None
    elements = []  # [name, count, [(name, type, list_count_type or None)]]
    for line in header:
        w = line.split()
        if not w:
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "element":
            elements.append([w[1], int(w[2]), []])
        elif w[0] == "property":
            if w[1] == "list":
                elements[-1][2].append((w[4], w[3], w[2]))
            else:
                elements[-1][2].append((w[2], w[1], None))
    verts, faces = [], []
    if fmt == "ascii":
        tokens = data[body:].split()
        pos = 0
        for name, count, props in elements:
            for _ in range(count):
                rec = {}
                for pname, ptype, ctype in props:
                    if ctype is None:
                        rec[pname] = float(tokens[pos])
                        pos += 1
                    else:
                        n = int(tokens[pos])
                        rec[pname] = [int(t) for t in tokens[pos + 1:pos + 1 + n]]
                        pos += 1 + n
                _store(name, rec, verts, faces)
    elif fmt in ("binary_little_endian", "binary_big_endian"):
        endian = "<" if fmt == "binary_little_endian" else ">"
        pos = body
        for name, count, props in elements:
            simple = all(c is None for _, _, c in props)
            if simple:
                st = struct.Struct(endian + "".join(PLY_TYPES[t] for _, t, _ in props))
                names = [p for p, _, _ in props]
                for _ in range(count):
                    rec = dict(zip(names, st.unpack_from(data, pos)))
                    pos += st.size
                    _store(name, rec, verts, faces)
                continue
            for _ in range(count):
                rec = {}
                for pname, ptype, ctype in props:
                    if ctype is None:
                        st = struct.Struct(endian + PLY_TYPES[ptype])
                        rec[pname] = st.unpack_from(data, pos)[0]
                        pos += st.size
                    else:
                        cs = struct.Struct(endian + PLY_TYPES[ctype])
                        n = cs.unpack_from(data, pos)[0]
                        pos += cs.size
                        ist = struct.Struct(endian + PLY_TYPES[ptype] * n)
                        rec[pname] = list(ist.unpack_from(data, pos))
                        pos += ist.size
                _store(name, rec, verts, faces)
    else:
        raise ValueError("%s: unsupported PLY format %s" % (path, fmt))
    return verts, faces


def _store(element, rec, verts, faces):
    if element == "vertex":
        verts.append((float(rec["x"]), float(rec["y"]), float(rec["z"])))
    elif element == "face":
        idx = rec.get("vertex_indices", rec.get("vertex_index"))
        for k in range(1, len(idx) - 1):
            faces.append((idx[0], idx[k], idx[k + 1]))


def read_stl(path):
    with open(path, "rb") as f:
        data = f.read()
    verts, faces, ids = [], [], {}

    def vid(p):
        if p not in ids:
            ids[p] = len(verts)
            verts.append(p)
        return ids[p]

    n = struct.unpack_from("<I", data, 80)[0] if len(data) >= 84 else -1
    if n >= 0 and len(data) == 84 + 50 * n:
        for t in range(n):
            v = struct.unpack_from("<12f", data, 84 + 50 * t)
            faces.append(tuple(vid(tuple(v[3 + 3 * c:6 + 3 * c])) for c in range(3)))
    else:  # ASCII
        corners = []
        for line in data.decode("ascii", errors="replace").splitlines():
            w = line.split()
            if w and w[0] == "vertex":
                corners.append(vid(tuple(float(x) for x in w[1:4])))
                if len(corners) == 3:
                    faces.append(tuple(corners))
                    corners = []
    return verts, faces


def read_mesh(path):
    ext = os.path.splitext(path)[1].lower()
    if ext == ".off":
        return read_off(path)
    if ext == ".ply":
        return read_ply(path)
    if ext == ".stl":
        return read_stl(path)
    raise ValueError("%s: unsupported format" % path)


# ---------------------------------------------------------------------------------------------

def compact(verts, faces):
    """Drops unreferenced vertices; returns (verts, faces, number dropped)."""
    used = sorted({i for f in faces for i in f})
    remap = {old: new for new, old in enumerate(used)}
    return ([verts[i] for i in used], [tuple(remap[i] for i in f) for f in faces],
            len(verts) - len(used))


def bbox(verts):
    lo = [min(v[k] for v in verts) for k in range(3)]
    hi = [max(v[k] for v in verts) for k in range(3)]
    return lo, hi


def to_float32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def write_ply(path, verts, faces):
    out = bytearray()
    out += (("ply\nformat binary_little_endian 1.0\ncomment meshdev reference test input\n"
             "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
             "element face %d\nproperty list uchar int vertex_indices\nend_header\n")
            % (len(verts), len(faces))).encode("ascii")
    vs = struct.Struct("<3f")
    for v in verts:
        out += vs.pack(*v)
    fs = struct.Struct("<B3i")
    for f in faces:
        out += fs.pack(3, *f)
    with open(path, "wb") as fh:
        fh.write(out)


def prepare_pair(name, path_a, path_b, scratch):
    """Writes A and B, compacted, moved and scaled by A's box, rounded to float32."""
    va, fa = read_mesh(path_a)
    vb, fb = read_mesh(path_b)
    va, fa, ua = compact(va, fa)
    vb, fb, ub = compact(vb, fb)
    lo, hi = bbox(va)
    centre = [(lo[k] + hi[k]) / 2 for k in range(3)]
    diag = math.sqrt(sum((hi[k] - lo[k]) ** 2 for k in range(3)))
    scale = TARGET_DIAGONAL / diag

    def tr(vs):
        return [tuple(to_float32((v[k] - centre[k]) * scale) for k in range(3)) for v in vs]

    va, vb = tr(va), tr(vb)
    lo, hi = bbox(va)
    diag_scaled = math.sqrt(sum((hi[k] - lo[k]) ** 2 for k in range(3)))
    out_a = os.path.join(scratch, name + "_A.ply")
    out_b = os.path.join(scratch, name + "_B.ply")
    write_ply(out_a, va, fa)
    write_ply(out_b, vb, fb)
    return {"a": out_a, "b": out_b, "nva": len(va), "nvb": len(vb), "unref_a": ua,
            "unref_b": ub, "scale": scale, "diag": diag_scaled}


MLX_FILTER = """ <filter name="Hausdorff Distance">
  <Param type="RichMesh" value="%(sampled)d" name="SampledMesh"/>
  <Param type="RichMesh" value="%(target)d" name="TargetMesh"/>
  <Param type="RichBool" value="false" name="SaveSample"/>
  <Param type="RichBool" value="true" name="SampleVert"/>
  <Param type="RichBool" value="false" name="SampleEdge"/>
  <Param type="RichBool" value="false" name="SampleFauxEdge"/>
  <Param type="RichBool" value="false" name="SampleFace"/>
  <Param type="RichInt" value="%(num)d" name="SampleNum"/>
  <Param type="RichAbsPerc" value="%(maxdist)g" min="0" max="%(maxmax)g" name="MaxDist"/>
 </filter>
"""


def run_meshlab(pair, scratch, name):
    """Both directions in one meshlabserver call; returns [stats A->B, stats B->A]."""
    num = max(pair["nva"], pair["nvb"]) + 1
    maxdist = 1000.0 * TARGET_DIAGONAL  # far above any distance: nothing may be dropped
    script = os.path.join(scratch, name + ".mlx")
    with open(script, "w") as f:
        f.write("<!DOCTYPE FilterScript>\n<FilterScript>\n")
        for sampled, target in ((0, 1), (1, 0)):
            f.write(MLX_FILTER % {"sampled": sampled, "target": target, "num": num,
                                  "maxdist": maxdist, "maxmax": 10 * maxdist})
        f.write("</FilterScript>\n")
    cmd = ["xvfb-run", "-a", "meshlabserver", "-i", pair["a"], "-i", pair["b"], "-s", script]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=300)
    text = p.stdout.decode("utf-8", errors="replace")
    with open(os.path.join(scratch, name + ".meshlab.log"), "w") as f:
        f.write(text)
    if p.returncode != 0:
        raise RuntimeError("meshlabserver exited with %d (log: %s.meshlab.log)"
                           % (p.returncode, name))
    results, count = [], None
    for line in text.splitlines():
        if not line.startswith("LOG: 2"):
            continue
        w = line.split()
        if "Sampled" in w and "pts" in w:
            count = int(w[w.index("Sampled") + 1])
        elif w[2:3] == ["min"] and count is not None:
            # "LOG: 2 min : a max b mean : c RMS : d"; the first such line after "Sampled"
            # is in absolute units, the second (w.r.t. the bbox diagonal) is skipped.
            results.append({"count": count, "min": float(w[4]), "max": float(w[6]),
                            "mean": float(w[9]), "rms": float(w[12])})
            count = None
    if len(results) != 2:
        raise RuntimeError("could not parse meshlabserver's log (%s.meshlab.log)" % name)
    return results


def run_meshdev(meshdev, a, b, out_json):
    cmd = [meshdev, "compare", a, b, "--sampling", "vertices", "--direction", "forward",
           "--json", out_json, "-q"]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=300)
    if p.returncode != 0:
        raise RuntimeError("meshdev exited with %d: %s"
                           % (p.returncode, p.stdout.decode(errors="replace").strip()))
    with open(out_json) as f:
        d = json.load(f)
    g = d["directions"]["forward"]["stats"]["geometry"]
    return {"count": int(g["count"]), "min": g["min"], "max": g["max"], "mean": g["mean"],
            "rms": g["rms"], "referenced": d["meshes"]["a"]["referenced_vertices"]}


# ---------------------------------------------------------------------------------------------

def cgal_mesh(name, scratch):
    if not os.path.exists(CGAL_ARCHIVE):
        return None
    out = os.path.join(scratch, "cgal", name)
    if not os.path.exists(out):
        os.makedirs(os.path.dirname(out), exist_ok=True)
        with tarfile.open(CGAL_ARCHIVE, "r:gz") as t:
            try:
                member = t.getmember("data/meshes/" + name)
            except KeyError:
                return None
            with t.extractfile(member) as src, open(out, "wb") as dst:
                shutil.copyfileobj(src, dst)
    return out


def shared(rel):
    p = os.path.join(SHARED_DATA, rel)
    return p if os.path.exists(p) else None


def decimated_bunny(scratch):
    src = cgal_mesh("bunny00.off", scratch)
    tool = shutil.which("OpenMesh-commandlineDecimater")
    if src is None or tool is None:
        return None
    out = os.path.join(scratch, "bunny_10.off")
    if not os.path.exists(out):
        subprocess.run([tool, "-M", "Q", "-n", "-3770", "-i", src, "-o", out],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=300)
    return out if os.path.exists(out) else None


def pairs(scratch):
    """(name, A, B) for every pair whose files are available; skipped pairs are reported."""
    out, skipped = [], []
    candidates = [
        ("anchor_dense-anchor", lambda: cgal_mesh("anchor_dense.off", scratch),
         lambda: cgal_mesh("anchor.off", scratch), "libcgal-demo"),
        ("elephant-refined", lambda: cgal_mesh("elephant.off", scratch),
         lambda: cgal_mesh("refined_elephant.off", scratch), "libcgal-demo"),
        ("bunny00-openmesh10", lambda: cgal_mesh("bunny00.off", scratch),
         lambda: decimated_bunny(scratch), "libcgal-demo + libopenmesh-apps"),
        ("knot-vcg_simplified", lambda: shared("metro_knot/knot_orig.ply"),
         lambda: shared("metro_knot/knot_vcg_simplified.ply"), "../shared/data"),
        ("knot-max_simplified_stl", lambda: shared("metro_knot/knot_orig.ply"),
         lambda: shared("metro_knot/knot_max_simplified.STL"), "../shared/data"),
        ("bun_zipper-res2", lambda: shared("scalar/stanford_bunny/bun_zipper.ply"),
         lambda: shared("scalar/stanford_bunny/bun_zipper_res2.ply"), "../shared/data"),
    ]
    for name, fa, fb, source in candidates:
        a = fa()
        b = fb() if a else None
        if a and b:
            out.append((name, a, b))
        else:
            skipped.append((name, source))
    return out, skipped


def rel_diff(x, ref):
    if x == ref:
        return 0.0
    return abs(x - ref) / max(abs(ref), 1e-300)


def main(argv):
    if len(argv) != 3:
        print("usage: %s MESHDEV_BINARY SCRATCH_DIR" % argv[0], file=sys.stderr)
        return 2
    meshdev, scratch = os.path.abspath(argv[1]), os.path.abspath(argv[2])
    missing = [t for t in ("meshlabserver", "xvfb-run") if shutil.which(t) is None]
    if missing:
        print("SKIP: %s not found on PATH (Debian: apt-get install meshlab xvfb xauth)"
              % " and ".join(missing))
        return SKIP
    if not os.access(meshdev, os.X_OK):
        print("error: %s is not an executable" % meshdev, file=sys.stderr)
        return 2
    os.makedirs(scratch, exist_ok=True)

    todo, skipped = pairs(scratch)
    for name, source in skipped:
        print("note: pair %s skipped (%s not available)" % (name, source))
    if not todo:
        print("SKIP: no mesh pair available")
        return SKIP

    passed = failed = loose = 0
    header = ("%-24s %-3s %-6s %17s %16s %9s %9s %s" %
              ("pair", "dir", "stat", "meshdev", "meshlab", "rel.diff", "abs/diag", "verdict"))
    print("Units: scaled so that A's bbox diagonal = %g (values / %g = fraction of diagonal)."
          % (TARGET_DIAGONAL, TARGET_DIAGONAL))
    print(header)
    print("-" * len(header))
    for name, a, b in todo:
        try:
            pair = prepare_pair(name, a, b, scratch)
            ml = run_meshlab(pair, scratch, name)
            md = [run_meshdev(meshdev, pair["a"], pair["b"], os.path.join(scratch, name + ".fw.json")),
                  run_meshdev(meshdev, pair["b"], pair["a"], os.path.join(scratch, name + ".bw.json"))]
        except Exception as e:  # a tool failed: the pair fails, the others still run
            print("%-24s FAILED: %s" % (name, e))
            failed += 2
            continue
        if pair["unref_a"] or pair["unref_b"]:
            print("%-24s note: removed unreferenced vertices: A %d, B %d"
                  % (name, pair["unref_a"], pair["unref_b"]))
        diag = pair["diag"]
        for k, direction in enumerate(("A>B", "B>A")):
            m, l = md[k], ml[k]
            ok = m["count"] == l["count"]
            strict = ok
            print("%-24s %-3s %-6s %17d %16d %9s %9s %s" % (
                name, direction, "count", m["count"], l["count"], "", "",
                "ok" if ok else "FAIL"))
            for stat in ("min", "max", "mean", "rms"):
                r = rel_diff(m[stat], l[stat])
                a_rel = abs(m[stat] - l[stat]) / diag
                st = r <= REL_TOL or (stat == "min" and a_rel <= STRICT_MIN_ABS_TOL)
                good = st or a_rel <= FLOAT_NOISE
                strict = strict and st
                ok = ok and good
                print("%-24s %-3s %-6s %17.9g %16.6f %9.2e %9.2e %s" % (
                    name, direction, stat, m[stat], l[stat], r, a_rel,
                    "ok" if st else ("ok*" if good else "FAIL")))
            if ok:
                passed += 1
                if not strict:
                    loose += 1
            else:
                failed += 1
    print("tolerance: %g relative, or %g x bbox diagonal absolute (MeshLab's float32 noise); "
          "counts must be equal" % (REL_TOL, FLOAT_NOISE))
    print("ok* = passes only thanks to the float32 floor (fails \"%g relative; min %g x diagonal\"): "
          "%d of the passed rows" % (REL_TOL, STRICT_MIN_ABS_TOL, loose))
    print("%d passed, %d failed" % (passed, failed))
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
