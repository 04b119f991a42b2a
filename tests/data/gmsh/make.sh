# Writes the Gmsh files of this folder with Debian 12's Gmsh (4.8.4) from the .geo
# models here. Not run by the build or the tests: the files are committed.
#   cd tests/data/gmsh && bash make.sh
set -euo pipefail
opts="-3 -clmax 2.5 -v 0"
# A coax of four physical volumes and two physical surfaces, partitioned in three
# (text and binary): the elements are in partition entities.
gmsh coax.geo $opts -part 3 -format msh41 -o coax_part3.msh
gmsh coax.geo $opts -part 3 -format msh41 -bin -o coax_part3_bin.msh
# Gmsh's own VTK export: tets and the physical surfaces' triangles, each with its
# physical group in the cell array CellEntityIds.
gmsh coax.geo $opts -format vtk -o coax.vtk
# Its Nastran export with physical tags as PIDs (CTRIA3 for the physical surfaces).
gmsh coax.geo $opts -format bdf -setnumber Mesh.SaveElementTagType 2 -o coax.bdf
# Second-order (10-node) tets.
gmsh coax.geo $opts -order 2 -format msh41 -o coax_order2.msh
# Tets and prisms.
gmsh mixed.geo -3 -v 0 -format msh41 -o mixed_prisms.msh
# Conductors in two physical groups each: Gmsh 2.2 writes their elements twice.
gmsh coax_two_groups.geo $opts -format msh22 -o coax_two_groups22.msh
# Third-order (20-node) tets, and the same mesh first-order.
gmsh cube.geo -3 -clmin 0.8 -clmax 0.8 -v 0 -order 3 -format msh41 -o cube_order3.msh
gmsh cube.geo -3 -clmin 0.8 -clmax 0.8 -v 0 -format msh41 -o cube_order1.msh
# Two boxes with surface groups that are a whole boundary, an interface, and part of
# a boundary; text and binary, both versions, and second order.
gmsh groups.geo -3 -clmax 0.5 -v 0 -format msh41 -o groups41.msh
gmsh groups.geo -3 -clmax 0.5 -v 0 -format msh41 -bin -o groups41_bin.msh
gmsh groups.geo -3 -clmax 0.5 -v 0 -format msh22 -o groups22.msh
gmsh groups.geo -3 -clmax 0.5 -v 0 -format msh22 -bin -o groups22_bin.msh
gmsh groups.geo -3 -clmax 0.5 -v 0 -order 2 -format msh41 -o groups_order2.msh
# A block with a round port on its flat top face (a group whose border is no crease).
gmsh port.geo -3 -clmax 0.1 -v 0 -format msh41 -o port.msh
# Overlapping surface groups (a face in two groups), text and binary.
gmsh overlap.geo -3 -clmax 0.5 -v 0 -format msh41 -o overlap41.msh
gmsh overlap.geo -3 -clmax 0.5 -v 0 -format msh41 -bin -o overlap41_bin.msh
# A block with two sheets inside it (embedded surfaces), in groups of their own and
# with a boundary face: surface groups inside one material.
gmsh sheet.geo -3 -clmax 0.25 -v 0 -format msh41 -o sheet.msh
# A ball with a thin spherical gap inside, bridged: two sheets of outer boundary 0.15
# apart, for the simplifier's guard against a boundary pushed through itself.
gmsh gap.geo -3 -clmax 0.9 -v 0 -format msh22 -o gap.msh
# A ball inside a shell, meshed apart: 0.15 apart, and touching (chords that cross), for
# the simplifier's guard between bodies.
gmsh apart.geo -3 -clmax 0.9 -v 0 -format msh22 -o apart.msh
gmsh apart.geo -3 -clmax 0.9 -v 0 -setnumber gap 0 -format msh22 -o touch.msh
# A bead in a shell's cavity, near its wall, meshed apart.
gmsh bead.geo -3 -clmax 0.9 -v 0 -format msh22 -o bead.msh
# A patch antenna: thin patch and ground plane (0.2 thick) and a feed pin (the
# simplifier's property tests).
gmsh antenna.geo -3 -clmax 2.5 -clmin 0.15 -v 0 -format msh22 -o antenna.msh
