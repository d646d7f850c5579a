#!/usr/bin/python3
"""Run VTK's vtkQuadricDecimation on a PLY mesh for meshdev's vtk-quadric backend.

usage: vtk_quadric.py IN.ply OUT.ply --faces N [--color-weight W] [--normal-weight W]
                      [--texcoord-weight W] [--no-attributes]

Reads IN.ply with vtkPLYReader (positions, red/green/blue, nx/ny/nz, u/v), decimates to about N
triangles with the attribute error metric on (Hoppe 1999 style: colours, normals and UVs are part
of the quadric and interpolated at the optimal position), and writes OUT.ply as ASCII PLY
(double positions, float normals/UVs, uchar colours) for meshdev's validating reader.
Run it with /usr/bin/python3 (Debian's python3-vtk9), not a pyenv interpreter.
Exit codes: 0 ok, 2 bad arguments, 3 unreadable input.
"""
import argparse
import sys

from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkQuadricDecimation, vtkTriangleFilter
from vtkmodules.vtkIOPLY import vtkPLYReader


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("input")
    ap.add_argument("output")
    ap.add_argument("--faces", type=int, required=True)
    ap.add_argument("--color-weight", type=float, default=0.1)
    ap.add_argument("--normal-weight", type=float, default=0.1)
    ap.add_argument("--texcoord-weight", type=float, default=0.1)
    ap.add_argument("--no-attributes", action="store_true")
    a = ap.parse_args()

    reader = vtkPLYReader()
    reader.SetFileName(a.input)
    reader.Update()
    mesh = reader.GetOutput()
    if mesh.GetNumberOfPolys() == 0:
        print("vtk_quadric.py: no faces read from %s" % a.input, file=sys.stderr)
        return 3
    tri = vtkTriangleFilter()
    tri.SetInputData(mesh)
    tri.Update()
    mesh = tri.GetOutput()
    faces = mesh.GetNumberOfPolys()
    reduction = max(0.0, min(1.0, 1.0 - float(a.faces) / float(faces)))

    dec = vtkQuadricDecimation()
    dec.SetInputData(mesh)
    dec.SetTargetReduction(reduction)
    dec.VolumePreservationOff()
    pd = mesh.GetPointData()
    if not a.no_attributes:
        dec.AttributeErrorMetricOn()
        dec.SetScalarsAttribute(pd.GetScalars() is not None)
        dec.SetNormalsAttribute(pd.GetNormals() is not None)
        dec.SetTCoordsAttribute(pd.GetTCoords() is not None)
        dec.VectorsAttributeOff()
        dec.TensorsAttributeOff()
        dec.SetScalarsWeight(a.color_weight)
        dec.SetNormalsWeight(a.normal_weight)
        dec.SetTCoordsWeight(a.texcoord_weight)
    dec.Update()
    write_ply(a.output, dec.GetOutput())
    return 0


def write_ply(path, mesh):
    points = mesh.GetPoints()
    n = mesh.GetNumberOfPoints()
    pd = mesh.GetPointData()
    colors = pd.GetScalars()
    if colors is not None and colors.GetNumberOfComponents() < 3:
        colors = None
    normals = pd.GetNormals()
    uvs = pd.GetTCoords()
    polys = mesh.GetPolys()
    tris = []
    ids = polys.GetData()
    i = 0
    total = ids.GetNumberOfTuples()
    while i < total:
        k = int(ids.GetValue(i))
        if k == 3:
            tris.append((int(ids.GetValue(i + 1)), int(ids.GetValue(i + 2)), int(ids.GetValue(i + 3))))
        i += k + 1
    with open(path, "w") as out:
        out.write("ply\nformat ascii 1.0\ncomment written by meshdev vtk_quadric.py\n")
        out.write("element vertex %d\n" % n)
        out.write("property double x\nproperty double y\nproperty double z\n")
        if normals is not None:
            out.write("property float nx\nproperty float ny\nproperty float nz\n")
        if colors is not None:
            out.write("property uchar red\nproperty uchar green\nproperty uchar blue\n")
        if uvs is not None:
            out.write("property float u\nproperty float v\n")
        out.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n" % len(tris))
        for v in range(n):
            p = points.GetPoint(v)
            row = ["%.17g" % p[0], "%.17g" % p[1], "%.17g" % p[2]]
            if normals is not None:
                row += ["%.9g" % x for x in normals.GetTuple3(v)]
            if colors is not None:
                c = colors.GetTuple(v)
                row += ["%d" % max(0, min(255, int(round(x)))) for x in c[:3]]
            if uvs is not None:
                row += ["%.9g" % x for x in uvs.GetTuple2(v)]
            out.write(" ".join(row) + "\n")
        for t in tris:
            out.write("3 %d %d %d\n" % t)


if __name__ == "__main__":
    sys.exit(main())
