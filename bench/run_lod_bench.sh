#!/usr/bin/env bash
# Simplifies a generated motor and times LOD replay over its whole history.
#   bash bench/run_lod_bench.sh [TETS] [SIZE]
set -euo pipefail
cd "$(dirname "$0")/.."
tets=${1:-1000000}
size=${2:-12}
[ -x build/bench/bench_lod ] || bash scripts/setup.sh
mkdir -p build/bench-data
mesh=build/bench-data/motor_${tets}.mesh
[ -f "$mesh" ] || ./build/app/tetlod generate motor --tets "$tets" -o "$mesh"
./build/bench/bench_lod "$mesh" --size "$size" --tolerance 0.05 --repeat 5
