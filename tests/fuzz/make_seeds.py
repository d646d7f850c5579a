#!/usr/bin/python3
"""Seed corpora for the fuzz targets.

Usage: make_seeds.py OUT_DIR
Writes OUT_DIR/fuzz_read_mesh (every case of tests/corpus/make_bad_inputs.py plus tiny valid
files) and OUT_DIR/fuzz_nearest_point, OUT_DIR/fuzz_simplify (byte strings in the layout of
tests/fuzz/fuzz_input.h: a tetrahedron, a square, degenerate and random small meshes; fixed seed).
"""
import os
import random
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.join(here, "..", "corpus"))
import make_bad_inputs  # noqa: E402

TINY = {
    "tri.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n",
    "quad.off": b"COFF\n4 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n0 1 0 9 9 9 255\n4 0 1 2 3\n",
    "tri_ascii.ply": b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                     b"property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                     b"element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                     b"0 0 0 1 2 3\n1 0 0 4 5 6\n0 1 0 7 8 9\n3 0 1 2\n",
    "tri.stl": b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
               b"endloop\nendfacet\nendsolid t\n",
}


def lattice(v):
    """The fuzz_input.h byte of a lattice value."""
    return max(0, min(239, int(round(v * 16 + 120))))


def mesh_bytes(verts, faces):
    out = bytes([(len(verts) - 1) % 16]) + bytes(lattice(c) for v in verts for c in v)
    return out + bytes([(len(faces) - 1) % 32]) + bytes(i for f in faces for i in f)


def main():
    out = sys.argv[1]
    read_dir = os.path.join(out, "fuzz_read_mesh")
    os.makedirs(read_dir, exist_ok=True)
    for i, (name, data, _, _, _) in enumerate(make_bad_inputs.CASES):
        if data is not None and data != b"DIR" and len(data) <= 65536:
            with open(os.path.join(read_dir, "corpus_%03d" % i), "wb") as f:
                f.write(data)
    for name, data in TINY.items():
        with open(os.path.join(read_dir, "valid_" + name), "wb") as f:
            f.write(data)
    tet = mesh_bytes([(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)], [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)])
    square = mesh_bytes([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [(0, 1, 2), (0, 2, 3)])
    degenerate = mesh_bytes([(0, 0, 0), (1, 0, 0), (2, 0, 0)], [(0, 1, 2), (0, 0, 1), (2, 2, 2)])
    book = mesh_bytes([(0, 0, 0), (1, 0, 0), (0.5, 1, 0), (0.5, 0, 1), (0.5, -1, 0)],
                      [(0, 1, 2), (0, 1, 3), (1, 0, 4), (0, 1, 2)])
    rng = random.Random(7)
    randoms = [bytes(rng.randrange(256) for _ in range(rng.randrange(8, 200))) for _ in range(20)]
    queries = bytes([lattice(0.3), lattice(0.2), lattice(1.5), 250, 120, 130, 248, 249, 120])
    for target, prefix in (("fuzz_nearest_point", b""), ("fuzz_simplify", b"\x07")):
        d = os.path.join(out, target)
        os.makedirs(d, exist_ok=True)
        seeds = [tet, square, degenerate, book] + randoms
        for i, s in enumerate(seeds):
            with open(os.path.join(d, "seed_%02d" % i), "wb") as f:
                f.write(prefix + s + queries)
    print("seed corpora written to %s" % out)


if __name__ == "__main__":
    main()
