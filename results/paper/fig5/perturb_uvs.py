#!/usr/bin/env python3
"""Fig. 5(c): a copy of the simplified bunny with high texture distortion.

Reads the binary PLY written by `meshdev simplify` (double x y z; faces: vertex_indices,
texcoord list, red green blue uchar, alpha float) and shifts the texture coordinates of every face
corner whose vertex lies in the top 25 % of the bounding box in y (the ears and the top of the
head) by (du, dv). Geometry is unchanged, so any deviation this adds is texture distortion only.
Usage: perturb_uvs.py IN.ply OUT.ply [du dv]
"""
import struct
import sys


def main():
    src, dst = sys.argv[1], sys.argv[2]
    du = float(sys.argv[3]) if len(sys.argv) > 3 else 0.08
    dv = float(sys.argv[4]) if len(sys.argv) > 4 else 0.05
    data = open(src, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    nv = nf = 0
    for line in header:
        if line.startswith("element vertex"):
            nv = int(line.split()[2])
        if line.startswith("element face"):
            nf = int(line.split()[2])
    expected = ["property double x", "property double y", "property double z",
                "property list uchar int vertex_indices", "property list uchar float texcoord",
                "property uchar red", "property uchar green", "property uchar blue",
                "property float alpha"]
    props = [l for l in header if l.startswith("property")]
    if props != expected:
        sys.exit("unexpected PLY layout: %s" % props)
    pos = end
    ys = []
    for _ in range(nv):
        ys.append(struct.unpack_from("<3d", data, pos)[1])
        pos += 24
    y_cut = min(ys) + 0.75 * (max(ys) - min(ys))
    out = bytearray(data[:pos])
    shifted = 0
    for _ in range(nf):
        n = data[pos]
        idx = struct.unpack_from("<%di" % n, data, pos + 1)
        pos += 1 + 4 * n
        m = data[pos]
        uv = list(struct.unpack_from("<%df" % m, data, pos + 1))
        for c in range(n):
            if ys[idx[c]] > y_cut:
                uv[2 * c] += du
                uv[2 * c + 1] += dv
                shifted += 1
        out += bytes([n]) + struct.pack("<%di" % n, *idx)
        out += bytes([m]) + struct.pack("<%df" % m, *uv)
        pos += 1 + 4 * m
        out += data[pos:pos + 7]
        pos += 7
    out += data[pos:]
    open(dst, "wb").write(bytes(out))
    print("shifted %d of %d corners (y > %.4g) by (%g, %g)" % (shifted, 3 * nf, y_cut, du, dv))


if __name__ == "__main__":
    main()
