#!/usr/bin/env python3
"""Reads .vtk and .vtu files with VTK's own readers, as ParaView does.

For each file given, prints one line:
  PATH points=N tets=N triangles=N other=N material_sum=S first_point=X,Y,Z arrays=A,B,... digest=H
(the arrays' names with each space as %20), where H is a SHA-256 of what VTK holds after reading: the points, each cell's
type and points, and every point and cell array (all as float64 or int64, so
that the same mesh gives the same digest from any of the two formats).
Exits with status 1, printing VTK's message, if VTK reports any warning or error.
"""
import hashlib
import sys

import numpy
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def main(paths):
    messages = vtk.vtkStringOutputWindow()
    vtk.vtkOutputWindow.SetInstance(messages)
    for path in paths:
        if path.endswith(".vtu"):
            reader = vtk.vtkXMLUnstructuredGridReader()
        else:
            reader = vtk.vtkUnstructuredGridReader()
            reader.ReadAllScalarsOn()
            reader.ReadAllFieldsOn()
        reader.SetFileName(path)
        reader.Update()
        if messages.GetOutput().strip():
            print(path, "VTK said:", messages.GetOutput().strip())
            return 1
        grid = reader.GetOutput()
        digest = hashlib.sha256()
        points = vtk_to_numpy(grid.GetPoints().GetData()).astype(numpy.float64)
        digest.update(points.tobytes())
        types = vtk_to_numpy(grid.GetCellTypesArray()).astype(numpy.int64)
        digest.update(types.tobytes())
        cells = grid.GetCells()
        digest.update(vtk_to_numpy(cells.GetOffsetsArray()).astype(numpy.int64).tobytes())
        digest.update(vtk_to_numpy(cells.GetConnectivityArray()).astype(numpy.int64).tobytes())
        names = []
        for data in (grid.GetPointData(), grid.GetCellData()):
            for i in range(data.GetNumberOfArrays()):
                name = data.GetArrayName(i)
                names.append(name.replace(" ", "%20"))
                digest.update(name.encode())
                digest.update(vtk_to_numpy(data.GetArray(i)).astype(numpy.float64).tobytes())
        material = grid.GetCellData().GetArray("material")
        material_sum = int(vtk_to_numpy(material).astype(numpy.int64).sum()) if material else 0
        tets = int((types == 10).sum())
        triangles = int((types == 5).sum())
        first = ",".join(repr(float(x)) for x in points[0])
        print(f"{path} points={len(points)} tets={tets} triangles={triangles} "
              f"other={len(types) - tets - triangles} material_sum={material_sum} "
              f"first_point={first} arrays={','.join(names)} digest={digest.hexdigest()}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
