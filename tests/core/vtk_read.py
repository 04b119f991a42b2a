#!/usr/bin/env python3
"""Reads .vtk and .vtu files with VTK's own readers, as ParaView does.

  vtk_read.py FILE...
prints for each file one line:
  PATH points=N tets=N triangles=N other=N material_sum=S first_point=X,Y,Z
       arrays=A,B,... names=TAG:NAME,... digest=H
with the point and cell arrays' names, the field data's group_tag and group_name
rows (TetLOD's names of materials and groups), spaces, commas and percent signs
in names written as %20, %2C and %25, and H a SHA-256 of what VTK holds after
reading: the points, each cell's type and points, every point and cell array (all
as float64 or int64, so that the same mesh gives the same digest from either
format) and the names.

  vtk_read.py --resave FILE OUT MODE
writes what VTK read from FILE to OUT as VTK writes it: a .vtu in MODE ascii,
binary (inline base64) or appended (base64), zlib-compressed as by default; a
.vtk in MODE ascii or binary.

Exits with status 1, printing VTK's message, if VTK reports any warning or error.
"""
import hashlib
import sys

import numpy
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def quote(text):
    return text.replace("%", "%25").replace(" ", "%20").replace(",", "%2C")


def read(path):
    if path.endswith(".vtu"):
        reader = vtk.vtkXMLUnstructuredGridReader()
    else:
        reader = vtk.vtkUnstructuredGridReader()
        reader.ReadAllScalarsOn()
        reader.ReadAllFieldsOn()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def report(path, grid):
    digest = hashlib.sha256()
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(numpy.float64)
    digest.update(points.tobytes())
    types = vtk_to_numpy(grid.GetCellTypesArray()).astype(numpy.int64)
    digest.update(types.tobytes())
    cells = grid.GetCells()
    digest.update(vtk_to_numpy(cells.GetOffsetsArray()).astype(numpy.int64).tobytes())
    digest.update(vtk_to_numpy(cells.GetConnectivityArray()).astype(numpy.int64).tobytes())
    arrays = []
    for data in (grid.GetPointData(), grid.GetCellData()):
        for i in range(data.GetNumberOfArrays()):
            name = data.GetArrayName(i)
            arrays.append(quote(name))
            digest.update(name.encode())
            digest.update(vtk_to_numpy(data.GetArray(i)).astype(numpy.float64).tobytes())
    field = grid.GetFieldData()
    tags, names = field.GetAbstractArray("group_tag"), field.GetAbstractArray("group_name")
    rows = []
    if tags is not None and names is not None:
        for i in range(min(tags.GetNumberOfValues(), names.GetNumberOfValues())):
            rows.append("%d:%s" % (tags.GetValue(i), quote(names.GetValue(i))))
    digest.update(",".join(rows).encode())
    material = grid.GetCellData().GetArray("material")
    material_sum = int(vtk_to_numpy(material).astype(numpy.int64).sum()) if material else 0
    tets = int((types == 10).sum())
    triangles = int((types == 5).sum())
    first = ",".join(repr(float(x)) for x in points[0])
    print(f"{path} points={len(points)} tets={tets} triangles={triangles} "
          f"other={len(types) - tets - triangles} material_sum={material_sum} "
          f"first_point={first} arrays={','.join(arrays)} names={','.join(rows)} "
          f"digest={digest.hexdigest()}")


def resave(path, out, mode):
    grid = read(path)
    if out.endswith(".vtu"):
        # MODE[+uncompressed][+uint64]: VTK's data mode, without its default zlib
        # compression, with 64-bit block headers.
        mode, *options = mode.split("+")
        writer = vtk.vtkXMLUnstructuredGridWriter()
        {"ascii": writer.SetDataModeToAscii, "binary": writer.SetDataModeToBinary,
         "appended": writer.SetDataModeToAppended}[mode]()
        if "uncompressed" in options:
            writer.SetCompressorTypeToNone()
        if "uint64" in options:
            writer.SetHeaderTypeToUInt64()
    else:
        writer = vtk.vtkUnstructuredGridWriter()
        {"ascii": writer.SetFileTypeToASCII, "binary": writer.SetFileTypeToBinary}[mode]()
    writer.SetInputData(grid)
    writer.SetFileName(out)
    writer.Write()


def main(args):
    messages = vtk.vtkStringOutputWindow()
    vtk.vtkOutputWindow.SetInstance(messages)
    if args[:1] == ["--resave"]:
        resave(*args[1:4])
    else:
        for path in args:
            grid = read(path)
            if messages.GetOutput().strip():
                break
            report(path, grid)
    if messages.GetOutput().strip():
        print("VTK said:", messages.GetOutput().strip())
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
