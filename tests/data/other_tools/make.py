# Writes the files of this folder with VTK 9.1 and meshio 5.0 (Debian 12:
# apt-get install python3-vtk9 python3-meshio), from the bundled box2 model:
#   build/app/tetlod convert assets/box2.mesh /tmp/box2.vtk
#   build/app/tetlod convert assets/box2.mesh /tmp/box2.msh
#   build/app/tetlod convert assets/box2.mesh /tmp/box2.node
#   build/app/tetlod convert assets/box2.mesh /tmp/box2.bdf
#   /usr/bin/python3 tests/data/other_tools/make.py /tmp/box2.vtk tests/data/other_tools \
#       /tmp/box2.msh assets/box2.mesh /tmp/box2.ele /tmp/box2.bdf
# Not run by the build or the tests: the files are committed, so that the tests
# check TetLOD against what those tools really write without depending on them.
import sys

import meshio
import vtk

source, folder, gmsh_source, medit_source, tetgen_source, nastran_source = sys.argv[1:7]
reader = vtk.vtkUnstructuredGridReader()
reader.SetFileName(source)
reader.ReadAllScalarsOn()
reader.Update()


def vtk_xml(name, mode, compressor, header64=False, encode=False):
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetInputData(reader.GetOutput())
    w.SetFileName(folder + "/" + name)
    {"ascii": w.SetDataModeToAscii, "binary": w.SetDataModeToBinary,
     "appended": w.SetDataModeToAppended}[mode]()
    w.SetEncodeAppendedData(1 if encode else 0)
    {"none": w.SetCompressorTypeToNone, "zlib": w.SetCompressorTypeToZLib,
     "lz4": w.SetCompressorTypeToLZ4}[compressor]()
    w.SetHeaderTypeToUInt64() if header64 else w.SetHeaderTypeToUInt32()
    w.Write()


vtk_xml("vtu_vtk9_binary_zlib.vtu", "binary", "zlib")
vtk_xml("vtu_vtk9_binary_none_uint64.vtu", "binary", "none", header64=True)
vtk_xml("vtu_vtk9_appended_zlib.vtu", "appended", "zlib")
vtk_xml("vtu_vtk9_appended_none_uint64.vtu", "appended", "none", header64=True)
vtk_xml("vtu_vtk9_appended_base64.vtu", "appended", "zlib", encode=True)
vtk_xml("vtu_vtk9_appended_lz4.vtu", "appended", "lz4")
vtk_xml("vtu_vtk9_ascii.vtu", "ascii", "none")  # with <InformationKey> after the values


def vtk_legacy(name, version):
    w = vtk.vtkUnstructuredGridWriter()
    w.SetInputData(reader.GetOutput())
    w.SetFileName(folder + "/" + name)
    w.SetFileTypeToBinary()
    w.SetFileVersion(version)
    w.Write()


vtk_legacy("vtk_vtk9_binary51.vtk", 51)
vtk_legacy("vtk_vtk9_binary42.vtk", 42)

mesh = meshio.read(source)
meshio.write(folder + "/vtu_meshio_zlib.vtu", mesh)  # binary, zlib: meshio's default
meshio.write(folder + "/vtu_meshio_lzma.vtu", mesh, compression="lzma")
meshio.write(folder + "/vtk_meshio_binary.vtk", mesh)  # binary by default
meshio.write(folder + "/msh_meshio_binary.msh", mesh, file_format="gmsh", binary=True)
meshio.write(folder + "/msh22_meshio_binary.msh", mesh, file_format="gmsh22", binary=True)
meshio.write(folder + "/nas_meshio.nas", mesh)
meshio.write(folder + "/inp_meshio.inp", mesh)

# What meshio writes for a mesh it read from Gmsh (cell data "gmsh:physical" and
# "gmsh:geometrical") or from Medit ("medit:ref"): the material is in those.
from_gmsh = meshio.read(gmsh_source)
meshio.write(folder + "/vtu_meshio_from_gmsh.vtu", from_gmsh)
meshio.write(folder + "/vtk_meshio_from_gmsh.vtk", from_gmsh, binary=False)
from_medit = meshio.read(medit_source)
meshio.write(folder + "/vtu_meshio_from_medit.vtu", from_medit)

# From TetGen and Nastran files (cell data "tetgen:ref", "nastran:ref"), and the
# legacy 4.2 layout in binary, whose 64-bit integer arrays meshio types "long".
meshio.write(folder + "/vtu_meshio_from_tetgen.vtu", meshio.read(tetgen_source))
meshio.write(folder + "/vtu_meshio_from_nastran.vtu", meshio.read(nastran_source))
meshio.vtk.write(folder + "/vtk42_meshio_binary_from_medit.vtk", from_medit, fmt_version="4.2",
                 binary=True)

# A mesh of two tetra cell blocks (one per material, as meshio holds a mesh read from
# a .inp or .msh with several element blocks): meshio's Medit writer writes one
# Tetrahedra section per block.
tets, refs = from_medit.cells_dict["tetra"], from_medit.cell_data["medit:ref"][0]
blocks = [tets[refs == m] for m in (1, 2)]
meshio.write(folder + "/mesh_meshio_two_blocks.mesh",
             meshio.Mesh(from_medit.points, [("tetra", b) for b in blocks],
                         cell_data={"medit:ref": [refs[refs == m] for m in (1, 2)]}))

# Medit binary (.meshb): meshio writes version 3 (4-byte integers, 8-byte keyword
# positions) for 32-bit cell arrays, version 4 (8-byte integers too) for 64-bit ones.
for bits, version in ((32, 3), (64, 4)):
    kind = "int%d" % bits
    meshio.write(folder + "/meshb_meshio_v%d.meshb" % version,
                 meshio.Mesh(from_medit.points, [("tetra", tets.astype(kind))],
                             cell_data={"medit:ref": [refs.astype(kind)]}))

# String arrays, as VTK writes names and records (the Exodus reader's "QA Records",
# "Information Records", block names): in the field data, and one string per cell,
# with a space, an empty string, a string of 70 bytes (whose length takes two bytes
# in a binary legacy file) and UTF-8 letters.
grid = vtk.vtkUnstructuredGrid()
grid.DeepCopy(reader.GetOutput())
names = vtk.vtkStringArray()
names.SetName("Information Records")
for text in ("iron core", "", "x" * 70, "Kupfer \u00e4\u00f6\u00fc \u03a9"):
    names.InsertNextValue(text)
grid.GetFieldData().AddArray(names)
labels = vtk.vtkStringArray()
labels.SetName("cell label")
for c in range(grid.GetNumberOfCells()):
    labels.InsertNextValue("cell %d" % c)
grid.GetCellData().AddArray(labels)
for file_type, name in ((1, "vtk_vtk9_strings_ascii.vtk"), (2, "vtk_vtk9_strings_binary.vtk")):
    w = vtk.vtkUnstructuredGridWriter()
    w.SetInputData(grid)
    w.SetFileName(folder + "/" + name)
    w.SetFileType(file_type)
    w.Write()
for mode, name in (("ascii", "vtu_vtk9_strings_ascii.vtu"), ("appended", "vtu_vtk9_strings_appended.vtu")):
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetInputData(grid)
    w.SetFileName(folder + "/" + name)
    w.SetDataModeToAscii() if mode == "ascii" else w.SetDataModeToAppended()
    w.Write()
