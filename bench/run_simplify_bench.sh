#!/usr/bin/env bash
# Times the whole simplification pipeline on a generated motor (median of 5).
#   bash bench/run_simplify_bench.sh [TETS] [SIZE]
# The defaults are issue 3's speed target: the ~200k-tet motor at the size docs/RESULTS.md
# takes for the paper's Fig. 4(b) (9.8), whose pipeline should take at most 0.7 s.
set -euo pipefail
cd "$(dirname "$0")/.."
tets=${1:-200000}
size=${2:-9.8}
[ -x build/bench/bench_simplify ] || bash scripts/setup.sh
mkdir -p build/bench-data
mesh=build/bench-data/motor_${tets}.mesh
[ -f "$mesh" ] || ./build/app/tetlod generate motor --tets "$tets" -o "$mesh"
./build/bench/bench_simplify "$mesh" --size "$size" --tolerance 0.05 --stretch 0.15 --valence 25 \
  --repeat 5
