#!/usr/bin/env bash
# Remakes the meshes of this folder with Gmsh (Debian 12: gmsh 4.8.4) from their .geo:
#   bash tests/data/topology/make.sh
# Not run by the build or the tests: the meshes are committed, so the tests do not
# depend on Gmsh's version.
set -euo pipefail
cd "$(dirname "$0")"
tetlod=../../../build/app/tetlod
for g in checker edge_touch vertex_touch; do
  gmsh -3 "$g.geo" -o "/tmp/tetlod_$g.msh" -format msh41 > /dev/null
  "$tetlod" convert "/tmp/tetlod_$g.msh" "$g.mesh"
  rm -f "/tmp/tetlod_$g.msh"
done
# Two bodies meshed apart, 0.4 from each other (a coarse tests/data/gmsh/apart.msh with a
# wider gap, so that the chords of the shell's inner wall stay clear of the ball).
gmsh -3 ../gmsh/apart.geo -clmax 1.6 -setnumber gap 0.4 -o /tmp/tetlod_apart.msh -format msh41 > /dev/null
"$tetlod" convert /tmp/tetlod_apart.msh apart.mesh
rm -f /tmp/tetlod_apart.msh
# A bead near the concave wall of a shell's cavity, meshed apart (tests/data/gmsh/bead.msh).
"$tetlod" convert ../gmsh/bead.msh bead.mesh
