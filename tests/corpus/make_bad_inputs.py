#!/usr/bin/python3
"""Writes the malformed-input corpus (and a few valid but nasty files) for `meshdev info`.

Usage: make_bad_inputs.py OUT_DIR

Each case becomes one file in OUT_DIR; OUT_DIR/cases.tsv lists, tab-separated:
file, expected exit code, expected substring, description. For errors (exit 3) the substring must
appear in stderr (with the file name); for valid files (exit 0) it must appear in stdout.
Stdlib only; binary files are built with struct.pack; "random" bytes use a fixed seed.
"""
import os
import random
import struct
import sys

CASES = []  # (name, bytes or None, exit code, substring, description)


def case(name, data, code, expect, what):
    if isinstance(data, str):
        data = data.encode("utf-8")
    CASES.append((name, data, code, expect, what))


def bad(name, data, expect, what):
    case(name, data, 3, expect, what)


def ok(name, data, expect, what):
    case(name, data, 0, expect, what)


rng = random.Random(20240607)


def junk(n, printable=False):
    if printable:
        alphabet = b"qwzxjk%$@!^&*()[]{}<>?~|"
        return bytes(rng.choice(alphabet) for _ in range(n))
    return bytes(rng.randrange(256) for _ in range(n))


TRI_OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

# ---------------------------------------------------------------- OBJ
bad("obj_empty.obj", b"", "empty file", "0-byte OBJ")
bad("obj_only_comment.obj", "# nothing here\n\n", "no vertices", "OBJ without any v line")
bad("obj_index_zero.obj", TRI_OBJ + "f 0 1 2\n", "index 0", "OBJ index 0 (indices are 1-based)")
bad("obj_index_out_of_range.obj", TRI_OBJ + "f 1 2 4\n", "out of range", "face index past the last vertex")
bad("obj_negative_before_first.obj", TRI_OBJ + "f -1 -2 -4\n", "refers before the first",
    "relative index reaching before vertex 1")
bad("obj_huge_index.obj", TRI_OBJ + "f 1 2 99999999999999999999\n", "out of range",
    "index that overflows 64-bit")
bad("obj_two_corners.obj", TRI_OBJ + "f 1 2\n", "at least 3", "face with 2 corners")
bad("obj_nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "not a finite", "nan coordinate")
bad("obj_inf.obj", "v 0 inf 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "not a finite", "inf coordinate")
bad("obj_overflow.obj", "v 0 0 1e400\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "not a finite",
    "coordinate overflowing double")
bad("obj_non_numeric.obj", "v a b c\n", "is not a number", "letters as coordinates")
bad("obj_missing_z.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "needs 3 coordinates", "vertex without z")
bad("obj_partial_vt.obj", TRI_OBJ + "vt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3\n", "differ in which of vt/vn",
    "face with vt on only some corners")
bad("obj_vt_out_of_range.obj", TRI_OBJ + "vt 0 0\nf 1/1 2/5 3/1\n", "texture coordinate index 5 out of range",
    "vt index past the last vt")
bad("obj_bad_index_token.obj", TRI_OBJ + "f 1 2 x\n", "not an integer", "letter as a face index")
bad("obj_random_bytes.obj", b"\x8f\x02" + junk(4094), "unknown OBJ keyword", "4 KiB of random bytes named .obj")
bad("obj_long_garbage_line.obj", TRI_OBJ + "v 1 2 " + "7" * 300000 + "garbage\n", "is not a number",
    "300 kB line ending in garbage")
bad("obj_vn_two_values.obj", TRI_OBJ + "vn 0 1\n", "needs 3 values", "normal with 2 components")
bad("obj_color_some_vertices.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "colours must be given",
    "vertex colours on only some vertices")
bad("obj_bad_corner_syntax.obj", TRI_OBJ + "f 1/1/1/1 2 3\n", "bad face corner", "corner with three slashes")

# ---------------------------------------------------------------- PLY ascii
def ply_ascii(vertex_count=3, face_count=1, body=None, props="property float x\nproperty float y\nproperty float z\n",
              face_prop="property list uchar int vertex_indices\n", fmt="ascii 1.0", extra_header=""):
    head = "ply\nformat %s\n%selement vertex %s\n%selement face %s\n%send_header\n" % (
        fmt, extra_header, vertex_count, props, face_count, face_prop)
    if body is None:
        body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
    return head + body


bad("plya_no_end_header.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n", "no 'end_header'",
    "header cut before end_header (OpenMesh loops forever)")
bad("plya_header_over_64k.ply", "ply\nformat ascii 1.0\n" + ("comment " + "x" * 90 + "\n") * 800,
    "64 KiB", "70 kB of comments and no end_header")
bad("plya_vertex_count_too_large.ply", ply_ascii(vertex_count=5), "declares 5 records",
    "vertex count larger than the data")
bad("plya_face_count_too_large.ply", ply_ascii(face_count=2, body="0 0 0\n1 0 0\n0 1 0\n3 0 1 2          \n"),
    "file ends after 1 of 2 face records", "face count larger than the data (OpenMesh adds a phantom face)")
bad("plya_face_count_too_small.ply", ply_ascii(body="0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n"), "extra data",
    "more faces than declared")
bad("plya_count_2g.ply", ply_ascii(vertex_count=2147483647), "declares 2147483647 records", "vertex count 2^31-1")
bad("plya_count_1e12.ply", ply_ascii(vertex_count=1000000000000), "too large", "vertex count 10^12")
bad("plya_count_negative.ply", ply_ascii(vertex_count=-3), "bad count", "negative vertex count")
bad("plya_count_abc.ply", ply_ascii(vertex_count="abc"), "bad count", "non-numeric vertex count")
bad("plya_nan.ply", ply_ascii(body="0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"), "not a finite", "nan coordinate")
bad("plya_inf.ply", ply_ascii(body="0 0 0\n1 -inf 0\n0 1 0\n3 0 1 2\n"), "not a finite", "-inf coordinate")
bad("plya_non_numeric.ply", ply_ascii(body="0 0 0\na b c\n0 1 0\n3 0 1 2\n"), "is not a number", "letters")
bad("plya_index_out_of_range.ply", ply_ascii(body="0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"), "out of range",
    "face index 7 with 3 vertices")
bad("plya_index_negative.ply", ply_ascii(body="0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"), "out of range", "negative index")
bad("plya_two_corners.ply", ply_ascii(body="0 0 0\n1 0 0\n0 1 0\n2 0 1\n"), "at least 3", "face with 2 corners")
bad("plya_missing_z.ply", ply_ascii(props="property float x\nproperty float y\n", body="0 0\n1 0\n0 1\n3 0 1 2\n"),
    "no scalar property 'z'", "vertex element without z")
bad("plya_unknown_type.ply", ply_ascii(props="property float128 x\nproperty float y\nproperty float z\n"),
    "unknown PLY type", "property type float128")
bad("plya_unknown_format.ply", ply_ascii(fmt="binary_middle_endian 1.0"), "unknown PLY format", "format name")
bad("plya_unknown_keyword.ply", ply_ascii(extra_header="elephant 3\n"), "unknown PLY header keyword",
    "unknown header keyword")
bad("plya_float_list_count.ply", ply_ascii(face_prop="property list float int vertex_indices\n"),
    "not an integer type", "list count type float")
bad("plya_float_list_items.ply", ply_ascii(face_prop="property list uchar float vertex_indices\n"),
    "floating-point item type", "vertex_indices with float items")
bad("plya_extra_value.ply", ply_ascii(body="0 0 0 5\n1 0 0\n0 1 0\n3 0 1 2\n"), "extra value",
    "vertex line with 4 values for 3 properties")
bad("plya_missing_value.ply", ply_ascii(body="0 0 0\n1 0\n0 1 0\n3 0 1 2\n"), "missing value", "vertex line with 2 values")
bad("plya_uchar_out_of_range.ply",
    ply_ascii(props="property float x\nproperty float y\nproperty float z\nproperty uchar red\n"
              "property uchar green\nproperty uchar blue\n",
              body="0 0 0 255 0 0\n1 0 0 300 0 0\n0 1 0 0 0 0\n3 0 1 2\n"), "out of range for its type",
    "uchar colour 300")
bad("plya_binary_body.ply", ply_ascii(body="") .encode() + struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    + struct.pack("<B3i", 3, 0, 1, 2), "is not a number", "ascii header, binary body")
bad("plya_no_vertex_element.ply", "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n",
    "no 'vertex' element", "no vertex element")
bad("plya_no_magic.ply", "pyl\nformat ascii 1.0\n", "no 'ply' magic", ".ply without the magic line")

# ---------------------------------------------------------------- PLY binary
def ply_bin(vertex_count=3, face_count=1, fmt="binary_little_endian", vprops=("float x", "float y", "float z"),
            fprop="list uchar int vertex_indices", extra=""):
    h = "ply\nformat %s 1.0\nelement vertex %d\n" % (fmt, vertex_count)
    h += "".join("property %s\n" % p for p in vprops)
    h += "element face %d\nproperty %s\n%send_header\n" % (face_count, fprop, extra)
    return h.encode()


V3 = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
F1 = struct.pack("<B3i", 3, 0, 1, 2)
bad("plyb_truncated_vertices.ply", ply_bin() + V3[:20], "declares 3 records", "file ends inside the vertices")
bad("plyb_truncated_face.ply", ply_bin() + V3 + F1[:7], "runs past the end", "file ends inside a face")
bad("plyb_count_2g.ply", ply_bin(vertex_count=2147483647) + V3 + F1, "declares 2147483647 records",
    "vertex count 2^31-1 with 3 vertices of data (OpenMesh: bad_alloc)")
bad("plyb_face_count_2g.ply", ply_bin(face_count=2147483647) + V3 + F1, "declares 2147483647 records",
    "face count 2^31-1 (OpenMesh: bad_alloc)")
bad("plyb_list_count_negative.ply", ply_bin(fprop="list int int vertex_indices") + V3 + struct.pack("<i", -1),
    "negative list count", "list count -1 (OpenMesh: bad_alloc)")
bad("plyb_list_count_255.ply", ply_bin() + V3 + struct.pack("<B3i", 255, 0, 1, 2), "runs past the end",
    "list count 255 with 3 items of data")
bad("plyb_index_out_of_range.ply", ply_bin() + V3 + struct.pack("<B3i", 3, 0, 1, 3), "out of range",
    "face index 3 with 3 vertices")
bad("plyb_index_negative.ply", ply_bin() + V3 + struct.pack("<B3i", 3, 0, -5, 2), "out of range", "negative index")
bad("plyb_two_corners.ply", ply_bin() + V3 + struct.pack("<B2i", 2, 0, 1), "at least 3", "face with 2 corners")
bad("plyb_nan.ply", ply_bin() + struct.pack("<9f", 0, 0, 0, float("nan"), 0, 0, 0, 1, 0) + F1, "not finite",
    "NaN float (OpenMesh keeps it)")
bad("plyb_inf_double.ply", ply_bin(vprops=("double x", "double y", "double z"))
    + struct.pack("<9d", 0, 0, 0, 1, 0, float("inf"), 0, 1, 0) + F1, "not finite", "inf double")
bad("plyb_junk_after_magic.ply", b"ply\nformat binary_little_endian 1.0\n" + junk(4096), "unknown PLY header keyword",
    "4 KiB of random bytes after the magic (OpenMesh: infinite loop, 729 MB of stderr)")
bad("plyb_extra_bytes.ply", ply_bin() + V3 + F1 + b"\x00" * 13, "13 bytes of extra data", "trailing bytes")
bad("plyb_ascii_body.ply", ply_bin() + b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "declares 3 records", "binary header, ascii body")
bad("plyb_be_truncated.ply", ply_bin(fmt="binary_big_endian") + struct.pack(">9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    + struct.pack(">B2i", 3, 0, 1), "runs past the end", "big-endian, last index missing")
bad("plyb_char_list_count_negative.ply", ply_bin(fprop="list char int vertex_indices") + V3 + struct.pack("<b", -2),
    "negative list count", "signed char list count -2")
bad("plyb_edge_truncated.ply", ply_bin(extra="element edge 4\nproperty int vertex1\nproperty int vertex2\n")
    + V3 + F1 + struct.pack("<2i", 0, 1), "declares 4 records", "unknown element cut short")

# ---------------------------------------------------------------- OFF
TRI_OFF = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
bad("off_empty.off", b"", "empty file", "0-byte OFF")
bad("off_no_keyword.off", "3 1 0\n" + TRI_OFF, "expected an OFF keyword", "counts without OFF")
bad("off_counts_too_large.off", "OFF\n10 5 0\n" + TRI_OFF, "header declares 10 vertices",
    "10 vertices/5 faces declared, 3/1 present (OpenMesh reads a face row as a vertex)")
bad("off_vertex_count_plus_one.off", "OFF\n4 1 0\n" + TRI_OFF + "# padding so that the size check passes\n",
    "vertex 3", "one vertex more declared than present")
bad("off_counts_too_small.off", "OFF\n3 1 0\n" + TRI_OFF + "3 2 1 0\n", "extra data", "two faces, one declared")
bad("off_count_2g.off", "OFF\n2000000000 1 0\n" + TRI_OFF, "header declares", "2e9 vertices (OpenMesh: bad_alloc)")
bad("off_count_1e12.off", "OFF\n1000000000000 1 0\n" + TRI_OFF, "header declares", "10^12 vertices")
bad("off_count_negative.off", "OFF\n-1 -1 0\n" + TRI_OFF, "negative count", "negative counts (OpenMesh: bad_alloc)")
bad("off_count_abc.off", "OFF\nabc 1 0\n" + TRI_OFF, "not an integer", "non-numeric count")
bad("off_nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "not a finite",
    "nan coordinate (OpenMesh drops every face)")
bad("off_overflow.off", "OFF\n3 1 0\n0 0 0\n1 1e400 0\n0 1 0\n3 0 1 2\n", "not a finite", "1e400")
bad("off_non_numeric.off", "OFF\n3 1 0\n0 0 0\nx y z\n0 1 0\n3 0 1 2\n", "is not a number", "letters")
bad("off_index_out_of_range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "out of range", "index 3 of 3")
bad("off_index_negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "out of range", "negative index")
bad("off_one_corner.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1 0      # padded\n", "at least 3", "face with 1 corner")
bad("off_valence_million.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1000000 0 1 2\n", "declares 1000000 corners",
    "face valence 10^6 with 3 indices")
bad("off_binary.off", b"OFF BINARY\n" + struct.pack(">3i", 3, 1, 0) + struct.pack(">9f", 0, 0, 0, 1, 0, 0, 0, 1, 0),
    "binary OFF is not supported", "OFF BINARY")
bad("off_missing_z.off", "OFF\n3 1 0\n0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "expected 3 values", "vertex without z")
bad("off_coff_two_components.off", "COFF\n3 1 0\n0 0 0 1 1\n1 0 0 1 1\n0 1 0 1 1\n3 0 1 2\n", "colour",
    "COFF vertex with 2 colour values")
bad("off_face_two_trailing.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 5 6\n", "values after the 3 indices",
    "face with 2 stray values after its indices")
bad("off_4off.off", "4OFF\n3 1 0\n0 0 0 0\n1 0 0 0\n0 1 0 0\n3 0 1 2\n", "expected an OFF keyword", "4D OFF")
bad("off_long_garbage.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 " + "5" * 200000 + "#\x01\n3 0 1 2\n",
    "not a finite", "200 kB number")

# ---------------------------------------------------------------- STL ascii
def facet(a, b, c, n="0 0 1"):
    return "facet normal %s\n outer loop\n  vertex %s\n  vertex %s\n  vertex %s\n endloop\nendfacet\n" % (n, a, b, c)


FACET = facet("0 0 0", "1 0 0", "0 1 0")
bad("stla_empty.stl", b"", "empty file", "0-byte STL (OpenMesh: success, 0 faces)")
bad("stla_truncated.stl", ("solid t\n" + FACET + facet("0 0 0", "1 0 0", "0 1 0"))[:120], "truncated",
    "cut off mid-vertex")
bad("stla_nan.stl", "solid t\n" + facet("0 0 0", "nan 0 0", "0 1 0") + "endsolid t\n", "not a finite",
    "nan (OpenMesh turns it into 0)")
bad("stla_inf.stl", "solid t\n" + facet("0 0 0", "1 inf 0", "0 1 0") + "endsolid t\n", "not a finite", "inf")
bad("stla_non_numeric.stl", "solid t\n" + facet("0 0 0", "a b c", "0 1 0") + "endsolid t\n", "is not a number", "letters")
bad("stla_missing_z.stl", "solid t\n" + facet("0 0 0", "1 0", "0 1 0") + "endsolid t\n", "is not a number", "vertex without z")
bad("stla_two_vertices.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid t\n",
    "facet with 2 vertices", "facet with 2 vertices")
bad("stla_four_vertices.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid t\n",
    "more than 3 vertices", "facet with 4 vertices")
bad("stla_no_endsolid.stl", "solid t\n" + FACET, "before 'endsolid'", "missing endsolid")
bad("stla_bad_keyword.stl", "solid t\n" + FACET + "facette normal 0 0 1\n" + "endsolid t\n", "expected 'facet'",
    "misspelt keyword")
bad("stla_no_facets.stl", "solid t\nendsolid t\n", "no facets", "ascii STL with no facets")
bad("stla_missing_endloop.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendfacet\nendsolid t\n",
    "expected 'endloop'", "facet without endloop")
bad("stla_long_garbage_line.stl", "solid t\nfacet normal 0 0 " + "9" * 300000 + "q\n", "is not a number",
    "300 kB garbage number")
bad("stla_not_solid.stl", "hello this is not an stl file\n", "too short", "short text that is no STL")

# ---------------------------------------------------------------- STL binary
def stl_bin(tris, count=None, header=b"binary stl".ljust(80, b"\0")):
    count = len(tris) if count is None else count
    body = b"".join(struct.pack("<12fH", 0, 0, 1, *t, 0) for t in tris)
    return header + struct.pack("<I", count) + body


T1 = (0, 0, 0, 1, 0, 0, 0, 1, 0)
T2 = (1, 0, 0, 1, 1, 0, 0, 1, 0)
bad("stlb_40_bytes.stl", b"\x01" * 40, "too short", "40-byte file (OpenMesh: success, 0 faces)")
bad("stlb_83_bytes.stl", b"\x00" * 83, "too short", "one byte short of a header")
bad("stlb_count_ffffffff.stl", stl_bin([T1], count=0xFFFFFFFF), "4294967295 triangles",
    "count 0xFFFFFFFF with one triangle of data")
bad("stlb_count_2_with_1_4.stl", stl_bin([T1, T2], count=2)[:84 + 70], "header says 2 triangles",
    "count 2 with 1.4 triangles of data")
bad("stlb_count_2g.stl", stl_bin([T1], count=2**31), "2147483648 triangles", "count 2^31")
bad("stlb_zero_triangles.stl", stl_bin([]), "0 triangles", "84-byte header with count 0")
bad("stlb_nan.stl", stl_bin([(0, 0, 0, float("nan"), 0, 0, 0, 1, 0)]), "non-finite", "NaN coordinate")
bad("stlb_inf.stl", stl_bin([(0, 0, 0, 1, 0, 0, 0, float("-inf"), 0)]), "non-finite", "-inf coordinate")
bad("stlb_extra_bytes.stl", stl_bin([T1]) + b"\x00" * 10, "header says 1 triangles", "10 bytes after the data")
bad("stlb_solid_header_bad_size.stl", stl_bin([T1, T2], header=b"solid evil".ljust(80, b" "))[:-3],
    "data is binary", "header starts with 'solid', binary data, wrong size")
bad("stlb_random.stl", junk(1000), "header says", "1000 random bytes")

# ---------------------------------------------------------------- other
bad("unknown_format.xyz", "1 2 3\n4 5 6\n", "unknown mesh format", "unknown extension, no magic")
bad("missing_file.obj", None, "cannot open", "file that does not exist (not generated)")
bad("a_directory.ply", "DIR", "cannot open", "a directory named .ply")
bad("t\u00e9tra\u00e8dre_\u2603.obj", TRI_OBJ + "f 0 1 2\n", "index 0", "non-ASCII file name")

# ---------------------------------------------------------------- valid but nasty (exit 0)
ok("valid_crlf.obj", (TRI_OBJ + "v 1 1 0\nf 1 2 3\nf 2 4 3\n").replace("\n", "\r\n"), "triangles     2",
   "CRLF line endings")
ok("valid_bom.ply", b"\xef\xbb\xbf" + ply_ascii().encode(), "triangles     1", "UTF-8 BOM before 'ply'")
ok("valid_crlf.ply", ply_ascii().replace("\n", "\r\n"), "triangles     1", "CRLF PLY")
ok("valid_polygons.off", "OFF\n# a quad and a pentagon\n6 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n-1 0.5 0\n2 0.5 0\n"
   "4 0 1 2 3\n5 0 3 4 3 3\n", "from 2 polygons", "polygon faces (fan triangulation)")
ok("valid_repeated_corner.ply", ply_ascii(body="0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n"), "1 of zero area",
   "face with a repeated corner")
ok("valid_unreferenced.obj", TRI_OBJ + "v 5 5 5\nf 1 2 3\n", "(1 unreferenced)", "unreferenced vertex kept")
ok("valid_point_cloud.ply", ply_ascii(face_count=0, body="0 0 0\n1 0 0\n0 1 0\n"), "triangles     0",
   "point cloud with 0 faces")
ok("valid_solid_header.stl", stl_bin([T1, T2], header=b"solid but really binary".ljust(80, b" ")),
   "triangles     2", "binary STL whose header starts with 'solid'")
ok("valid_big_endian.ply", ply_bin(fmt="binary_big_endian") + struct.pack(">9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
   + struct.pack(">B3i", 3, 0, 1, 2), "triangles     1", "big-endian binary PLY")
ok("valid_edge_element.ply", ply_bin(extra="element edge 2\nproperty int vertex1\nproperty list uchar int rest\n")
   + V3 + F1 + struct.pack("<iBi", 0, 1, 7) + struct.pack("<iB", 1, 0), "triangles     1",
   "unknown element with a list, skipped")
ok("valid_negative_indices.obj", TRI_OBJ + "f -3 -2 -1\n", "triangles     1", "relative OBJ indices")
ok("valid_ascii_two_solids.stl", "solid a\n" + FACET + "endsolid a\nsolid b\n" + facet("1 0 0", "1 1 0", "0 1 0")
   + "endsolid b\n", "vertices      4", "ascii STL with two solids, shared corners merged")
ok("valid_\u00fcmlaut.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "triangles     1", "non-ASCII name, valid")

# ---------------------------------------------------------------- more cases (issue 7: >= 20 per family)
# OBJ
bad("obj_crlf_index_zero.obj", (TRI_OBJ + "f 0 1 2\n").replace("\n", "\r\n"), "index 0",
    "CRLF line endings do not hide an index 0")
bad("obj_bom_bad_index.obj", b"\xef\xbb\xbf" + (TRI_OBJ + "f 1 2 9\n").encode(), "out of range",
    "UTF-8 BOM, then an out-of-range index")
bad("obj_truncated_vertex.obj", TRI_OBJ + "f 1 2 3\nv 1 2", "needs 3 coordinates", "file cut inside a v line")
bad("obj_index_int_overflow.obj", TRI_OBJ + "f 1 2 4294967299\n", "out of range",
    "index 2^32+3 (wraps to 3 in 32 bits)")
bad("obj_negative_huge.obj", TRI_OBJ + "f 1 2 -9223372036854775808\n", "refers before the first",
    "most negative 64-bit index")
bad("obj_one_corner.obj", TRI_OBJ + "f 1\n", "at least 3", "face with 1 corner")
bad("obj_no_corners.obj", TRI_OBJ + "f\n", "at least 3", "face with no corners")
bad("obj_minus_inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 -Infinity\nf 1 2 3\n", "not a finite", "-Infinity")
bad("obj_hex_float.obj", "v 0x1p3 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "is not a number", "hex float token")
bad("obj_vn_out_of_range.obj", TRI_OBJ + "vn 0 0 1\nf 1//1 2//2 3//1\n", "out of range", "vn index past the last vn")
bad("obj_nan_normal.obj", TRI_OBJ + "vn nan 0 1\nf 1//1 2//1 3//1\n", "not a finite", "nan normal")
bad("obj_binary_stl_named_obj.obj", b"\x00" * 80 + struct.pack("<I", 1) + struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0),
    "unknown OBJ keyword", "binary STL bytes named .obj (exact STL size)")
bad("obj_very_long_face.obj", TRI_OBJ + "f " + "1 2 " * 100000 + "0\n", "index 0",
    "200 001-corner face ending in index 0 (800 kB line)")
bad("obj_\u00e9\u00e8_\u4e2d\u6587.obj", TRI_OBJ + "f 1 2 3 4\n", "out of range", "non-ASCII file name, OBJ")
ok("valid_long_comment.obj", "# " + "x" * 2000000 + "\n" + TRI_OBJ + "f 1 2 3\n", "triangles     1",
   "2 MB comment line")
ok("valid_mtllib_dev_zero.obj", "mtllib /dev/zero\n" + TRI_OBJ + "f 1 2 3\n", "triangles     1",
   "mtllib naming /dev/zero: skipped with a warning (was: read without end, out of memory, exit 70)")
ok("valid_mtllib_directory.obj", "mtllib /\n" + TRI_OBJ + "f 1 2 3\n", "triangles     1",
   "mtllib naming a directory: skipped with a warning")
ok("valid_bom_crlf.obj", b"\xef\xbb\xbf" + (TRI_OBJ + "f 1 2 3\n").replace("\n", "\r\n").encode(),
   "triangles     1", "BOM and CRLF OBJ")

# PLY ascii
bad("plya_empty.ply", b"", "empty file", "0-byte PLY")
bad("plya_magic_only.ply", "ply\n", "no 'end_header'", "just the magic line")
bad("plya_truncated_body.ply", ply_ascii()[:-8], "declares 1 records", "body cut in the face line")
bad("plya_crlf_bad_index.ply", ply_ascii(body="0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n").replace("\n", "\r\n"),
    "out of range", "CRLF PLY with an index out of range")
bad("plya_bom_nan.ply", b"\xef\xbb\xbf" + ply_ascii(body="0 0 0\n1 0 0\n0 1 inf\n3 0 1 2\n").encode(),
    "not a finite", "BOM PLY with inf")
bad("plya_list_count_negative.ply", ply_ascii(body="0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n"), "out of range",
    "list count -3 for a uchar count")
bad("plya_list_count_short.ply", ply_ascii(body="0 0 0\n1 0 0\n0 1 0\n5 0 1 2\n"), "missing value",
    "list count 5 with 3 items")
bad("plya_list_count_huge.ply", ply_ascii(face_prop="property list uint int vertex_indices\n",
    body="0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n"), "missing value", "list count 4e9 with 3 items")
bad("plya_index_float.ply", ply_ascii(body="0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n"), "not an integer",
    "face index 2.5")
bad("plya_index_int_overflow.ply", ply_ascii(body="0 0 0\n1 0 0\n0 1 0\n3 0 1 4294967298\n"),
    "out of range", "index 2^32+2 for an int")
bad("plya_list_of_lists.ply", ply_ascii(face_prop="property list uchar list vertex_indices\n"),
    "unknown PLY type", "list item type 'list'")
bad("plya_very_long_line.ply", ply_ascii(body="0 0 0\n1 0 0\n0 1 " + "0" * 1000000 + "1x\n3 0 1 2\n"),
    "is not a number", "1 MB token")
bad("plya_huge_face_count.ply", ply_ascii(face_count=99999999999999999999), "bad count",
    "face count beyond 64 bits")
bad("plya_\u00fc\u00f1\u00ee\u00e7\u00f8d\u00e9.ply", ply_ascii(body="0 0 0\n1 0 0\n0 1 0\n2 0 1\n"), "at least 3",
    "non-ASCII file name, PLY ascii")
ok("valid_long_comment.ply", ply_ascii(extra_header="comment " + "y" * 30000 + "\n"), "triangles     1",
   "30 kB header comment")

# PLY binary
bad("plyb_empty_body.ply", ply_bin(), "declares 3 records", "binary header, no data")
bad("plyb_count_negative.ply", ply_bin(vertex_count=-1) + V3 + F1, "bad count", "negative vertex count")
bad("plyb_count_abc.ply", ply_bin().replace(b"vertex 3", b"vertex 3x") + V3 + F1, "bad count",
    "vertex count '3x'")
bad("plyb_uint_list_count_huge.ply", ply_bin(fprop="list uint int vertex_indices") + V3 + struct.pack("<I3i", 0xFFFFFFFF, 0, 1, 2),
    "runs past the end", "uint list count 0xFFFFFFFF")
bad("plyb_ushort_list_count.ply", ply_bin(fprop="list ushort int vertex_indices") + V3 + struct.pack("<H3i", 60000, 0, 1, 2),
    "runs past the end", "ushort list count 60000 with 3 items")
bad("plyb_uint_index_huge.ply", ply_bin(fprop="list uchar uint vertex_indices") + V3 + struct.pack("<B3I", 3, 0, 1, 0xFFFFFFFF),
    "out of range", "uint index 0xFFFFFFFF")
bad("plyb_double_list_count.ply", ply_bin(fprop="list double int vertex_indices") + V3 + struct.pack("<d3i", 3, 0, 1, 2),
    "not an integer type", "list count type double")
bad("plyb_float_items.ply", ply_bin(fprop="list uchar float vertex_indices") + V3 + struct.pack("<B3f", 3, 0, 1, 2),
    "floating-point item type", "vertex_indices with float items, binary")
bad("plyb_be_nan.ply", ply_bin(fmt="binary_big_endian") + struct.pack(">9f", 0, 0, 0, 1, 0, 0, 0, float("nan"), 0)
    + struct.pack(">B3i", 3, 0, 1, 2), "not finite", "big-endian NaN")
bad("plyb_le_read_as_be.ply", ply_bin(fmt="binary_big_endian") + V3 + F1, "out of range",
    "little-endian data under a big-endian header")
bad("plyb_one_corner.ply", ply_bin() + V3 + struct.pack("<Bi", 1, 0) + b"\x00" * 8, "at least 3",
    "face with 1 corner")
bad("plyb_zero_corners.ply", ply_bin() + V3 + struct.pack("<B", 0), "at least 3", "face with 0 corners")
bad("plyb_\u65e5\u672c.ply", ply_bin() + V3 + struct.pack("<B3i", 3, 0, 1, 5), "out of range",
    "non-ASCII file name, PLY binary")
ok("valid_crlf_header_binary.ply", ply_bin().replace(b"\n", b"\r\n") + V3 + F1, "triangles     1",
   "binary PLY whose header has CRLF line endings")

# OFF
bad("off_truncated_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1", "only 23 bytes follow", "file cut inside the face")
bad("off_crlf_index.off", "OFF\r\n3 1 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 5\r\n", "out of range",
    "CRLF OFF with an index out of range")
bad("off_bom_nan.off", b"\xef\xbb\xbfOFF\n3 1 0\n0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n", "not a finite", "BOM OFF with nan")
bad("off_index_float.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2.0\n", "not an integer", "index 2.0")
bad("off_valence_negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n", "at least 3", "valence -3")
bad("off_index_overflow.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 4294967296\n", "out of range",
    "index 2^32 (wraps to 0 in 32 bits)")
bad("off_two_corners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1 # pad pad\n", "at least 3", "face with 2 corners")
bad("off_zero_vertices.off", "OFF\n0 0 0\n", "vertices", "no vertices")
bad("off_\u00e5\u00df.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -2\n", "out of range", "non-ASCII file name, OFF")
ok("valid_long_comment.off", "OFF\n# " + "z" * 1500000 + "\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "triangles     1",
   "1.5 MB comment line")
ok("valid_crlf_bom.off", b"\xef\xbb\xbf" + b"OFF\r\n3 1 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n",
   "triangles     1", "BOM and CRLF OFF")

# STL ascii
bad("stla_solid_only.stl", "solid", "before 'endsolid'", "the word 'solid' and nothing else")
bad("stla_overflow.stl", "solid t\n" + facet("0 0 0", "1 0 1e999", "0 1 0") + "endsolid t\n", "not a finite",
    "1e999 overflows double")
bad("stla_extra_value.stl", "solid t\n" + facet("0 0 0", "1 0 0 7", "0 1 0") + "endsolid t\n", "extra",
    "vertex with 4 values")
bad("stla_missing_outer_loop.stl", "solid t\nfacet normal 0 0 1\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n",
    "expected 'outer'", "facet without 'outer loop'")
bad("stla_binary_body.stl", b"solid t\n" + struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0) * 3,
    "data is binary", "'solid' line followed by binary triangles (wrong size for binary)")
bad("stla_crlf_nan.stl", ("solid t\n" + facet("0 0 0", "1 0 0", "0 NaN 0") + "endsolid t\n").replace("\n", "\r\n"),
    "not a finite", "CRLF STL with NaN")
bad("stla_truncated_after_endloop.stl", "solid t\n" + FACET.replace("endfacet\n", ""), "truncated",
    "file ends before endfacet")
bad("stla_\u00f8\u00e6.stl", "solid t\n" + facet("0 0 0", "1 0 x", "0 1 0") + "endsolid t\n", "is not a number",
    "non-ASCII file name, STL ascii")
ok("valid_crlf.stl", ("solid t\n" + FACET + "endsolid t\n").replace("\n", "\r\n"), "triangles     1", "CRLF ascii STL")
ok("valid_long_solid_name.stl", "solid " + "n" * 1000000 + "\n" + FACET + "endsolid\n", "triangles     1",
   "1 MB solid name")

# STL binary
bad("stlb_84_bytes_count_1.stl", stl_bin([], count=1), "header says 1 triangles", "header only, count 1")
bad("stlb_count_larger.stl", stl_bin([T1, T2], count=3), "header says 3 triangles", "count 3 with 2 triangles")
bad("stlb_count_smaller.stl", stl_bin([T1, T2], count=1), "header says 1 triangles", "count 1 with 2 triangles")
bad("stlb_count_zero_with_data.stl", stl_bin([T1], count=0), "header says 0 triangles", "count 0 with 1 triangle")
bad("stlb_truncated_mid_triangle.stl", stl_bin([T1, T2])[:84 + 50 + 25], "header says 2 triangles",
    "cut in the middle of the 2nd triangle")
bad("stlb_ffffffff_no_data.stl", stl_bin([], count=0xFFFFFFFF), "4294967295 triangles", "count 0xFFFFFFFF, 84 bytes")
bad("stlb_signaling_nan.stl", stl_bin([T1])[:84 + 12 + 4] + struct.pack("<I", 0x7F800001) + stl_bin([T1])[84 + 20:],
    "non-finite", "signalling NaN bit pattern")
bad("stlb_inf_z.stl", stl_bin([(0, 0, float("inf"), 1, 0, 0, 0, 1, 0)]), "non-finite", "+inf z")
bad("stlb_solid_header_short.stl", b"solid x".ljust(80, b" ") + struct.pack("<I", 1) + b"\x00" * 30,
    "data is binary", "binary-looking 'solid' file, 114 bytes")
bad("stlb_\u00e4\u00f6\u00fc.stl", stl_bin([T1], count=7), "header says 7 triangles", "non-ASCII file name, STL binary")
ok("valid_nan_normal.stl", b"binary".ljust(80, b"\0") + struct.pack("<I", 1)
   + struct.pack("<12fH", float("nan"), 0, 1, *T1, 0), "triangles     1", "NaN facet normal (not used)")
ok("valid_attribute_bytes.stl", b"vendor colour".ljust(80, b"\0") + struct.pack("<I", 1)
   + struct.pack("<12fH", 0, 0, 1, *T1, 0x7C1F), "triangles     1", "non-zero attribute byte count, exact size")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_bad_inputs.py OUT_DIR")
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "cases.tsv"), "w", encoding="utf-8") as manifest:
        manifest.write("file\texpected_exit\texpected_substring\tdescription\n")
        for name, data, code, expect, what in CASES:
            path = os.path.join(out, name)
            if data == b"DIR":
                os.makedirs(path, exist_ok=True)
            elif data is not None:
                with open(path, "wb") as f:
                    f.write(data)
            manifest.write("%s\t%d\t%s\t%s\n" % (name, code, expect, what))
    print("%d cases written to %s" % (len(CASES), out))


if __name__ == "__main__":
    main()
