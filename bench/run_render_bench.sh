#!/usr/bin/env bash
# Times a full rebuild of the renderer's GPU buffers on a generated ~1M-tet motor.
#   bash bench/run_render_bench.sh [TETS]
set -euo pipefail
cd "$(dirname "$0")/.."
tets=${1:-1000000}
[ -x build/bench/bench_render ] || bash scripts/setup.sh
mkdir -p build/bench-data
mesh=build/bench-data/motor_${tets}.mesh
[ -f "$mesh" ] || ./build/app/tetlod generate motor --tets "$tets" -o "$mesh"
./build/bench/bench_render "$mesh" --repeat 5 --hide 1
