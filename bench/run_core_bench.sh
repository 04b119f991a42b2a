#!/usr/bin/env bash
# Generates a ~1M-tet motor (once, cached in build/bench-data) and runs bench_core.
#   bash bench/run_core_bench.sh [TETS]
set -euo pipefail
cd "$(dirname "$0")/.."
tets=${1:-1000000}
[ -x build/app/tetlod ] || bash scripts/setup.sh
mkdir -p build/bench-data
mesh=build/bench-data/motor_${tets}.mesh
[ -f "$mesh" ] || ./build/app/tetlod generate motor --tets "$tets" -o "$mesh"
ls -l "$mesh"
./build/bench/bench_core "$mesh" --repeat 5
