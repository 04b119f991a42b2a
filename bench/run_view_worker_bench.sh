#!/usr/bin/env bash
# How long a simplification takes in the viewer's worker thread against the same run
# in `tetlod simplify`, while the window keeps drawing (at most 32 frames a second
# while nothing moves: app/viewer.cpp, Viewer::frame()). Under Xvfb, OpenGL is
# llvmpipe, which draws on every core, so frames compete with the worker.
#   bash bench/run_view_worker_bench.sh [TETS] [SIZE] [RUNS]
# Prints, for each of RUNS alternating pairs, the run's time (subdivide + classify +
# simplify, and for a run past the valence both runs) in the CLI and in the viewer.
set -euo pipefail
cd "$(dirname "$0")/.."
tets=${1:-200000}
size=${2:-9.8}
runs=${3:-3}
[ -x build/app/tetlod ] || bash scripts/setup.sh
mkdir -p build/bench-data
mesh=build/bench-data/motor_${tets}.mesh
[ -f "$mesh" ] || ./build/app/tetlod generate motor --tets "$tets" -o "$mesh"
script=build/bench-data/view_worker.script
cat >"$script" <<SCRIPT
thresholds size=$size stretch=0.15 valence=25 tolerance=0.05
simplify
quit
SCRIPT
for ((i = 1; i <= runs; i++)); do
  cli=$(./build/app/tetlod simplify "$mesh" -o build/bench-data/view_worker_out.mesh \
    --size "$size" --tolerance 0.05 | grep '^time:')
  view=$(xvfb-run -a -s "-screen 0 1920x1200x24" ./build/app/tetlod view "$mesh" \
    --size 1280x800 --script "$script" | grep 'simplified:')
  echo "run $i: cli $cli"
  echo "run $i: view $view"
done
