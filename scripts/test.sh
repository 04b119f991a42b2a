#!/usr/bin/env bash
# Set-up plus the whole test suite: every test in the Release build, then the core
# tests again under AddressSanitizer + UndefinedBehaviorSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."
# gmsh: the test suite checks that Gmsh itself reads the .msh files TetLOD writes;
# calculix-ccx: that CalculiX runs an analysis on the .inp files TetLOD writes;
# getdp: that GetDP solves on the surface groups of the .msh files TetLOD writes;
# python3-vtk9 (with python3-numpy): that VTK, which ParaView is built on, reads the
# .vtk and .vtu files TetLOD writes, in text and in binary;
# strace: a signal injected between the renames of a command's files waits for the last.
# (setup.sh also installs xvfb + xauth: ctest runs the GLFW window test under
# xvfb-run; the golden-image tests render offscreen with OSMesa and need no display.)
TETLOD_EXTRA_PACKAGES="gmsh calculix-ccx getdp python3-vtk9 python3-numpy strace" bash scripts/setup.sh

jobs=$(nproc)
ctest --test-dir build --output-on-failure -j"$jobs"

werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTETLOD_SANITIZE=ON \
  -DTETLOD_CORE_ONLY=ON -DTETLOD_WERROR=$werror
cmake --build build-asan -j"$jobs"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan --output-on-failure -j"$jobs"
