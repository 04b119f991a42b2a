#!/usr/bin/env bash
# .vtk and .vtu written as text and in binary (--vtk-binary) from the ~1M-tet motor
# (generated once, cached in build/bench-data): the time TetLOD takes to write each
# (convert from .meshb, so that reading the input costs little), its size, and the
# time TetLOD (bench_core: read + validate), VTK 9 (Debian's python3-vtk9) and
# ParaView (pvbatch, Debian's paraview + python3-paraview) take to read it, where
# those are installed. ROUNDS rounds, the four files alternating. (Debian 12 cannot
# install python3-vtk9 and python3-paraview together; with the second, the "vtk"
# column is ParaView's own VTK.)
#   bash bench/run_vtk_bench.sh [TETS] [ROUNDS]
set -euo pipefail
cd "$(dirname "$0")/.."
tets=${1:-1000000}
rounds=${2:-3}
[ -x build/app/tetlod ] || bash scripts/setup.sh
mkdir -p build/bench-data build/bench-data/vtk
mesh=build/bench-data/motor_${tets}.mesh
[ -f "$mesh" ] || ./build/app/tetlod generate motor --tets "$tets" -o "$mesh"
dir=build/bench-data/vtk
./build/app/tetlod convert "$mesh" "$dir/in.meshb" > /dev/null
seconds() { # command...: wall seconds, to the millisecond
  local start end
  start=$(date +%s.%N)
  "$@" > /dev/null
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }'
}
python=""
for p in /usr/bin/python3 python3; do
  if "$p" -c 'import vtk' 2> /dev/null; then python=$p; break; fi
done
vtk_read='import sys, time, vtk
f = sys.argv[1]
r = vtk.vtkXMLUnstructuredGridReader() if f.endswith(".vtu") else vtk.vtkUnstructuredGridReader()
r.SetFileName(f)
t = time.time(); r.Update(); print("%.3f" % (time.time() - t))'
pv_read='import sys, time
from paraview.simple import OpenDataFile
t = time.time(); s = OpenDataFile(sys.argv[-1]); s.UpdatePipeline(); print("%.3f" % (time.time() - t))'
printf '%-14s %10s %8s %8s %8s %8s\n' file MB write tetlod vtk paraview
for ((round = 1; round <= rounds; ++round)); do
  for name in text.vtk binary.vtk text.vtu binary.vtu; do
    flag=""
    [[ $name == binary.* ]] && flag=--vtk-binary
    write=$(seconds ./build/app/tetlod convert "$dir/in.meshb" "$dir/$name" $flag)
    mb=$(($(stat -c %s "$dir/$name") / 1000000))
    ours=$(./build/bench/bench_core "$dir/$name" --repeat 1 | awk '/^read \+ validate/ {print $4}')
    vtk=-
    [ -n "$python" ] && vtk=$("$python" -c "$vtk_read" "$dir/$name")
    pv=-
    command -v pvbatch > /dev/null && pv=$(pvbatch -c "$pv_read" "$dir/$name" 2> /dev/null | tail -1 || echo -)
    printf '%-14s %10s %8s %8s %8s %8s\n' "$name" "$mb" "$write" "$ours" "$vtk" "$pv"
  done
done
echo "(seconds; write: tetlod convert from .meshb, whole process; tetlod: bench_core's read +"
echo " validate; vtk, paraview: the reader's update only)"
