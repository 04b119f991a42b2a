#!/usr/bin/env bash
# What a size map (--size-map, sizes at the input's vertices) costs against the region
# rule it samples: the 220k motor with the sizes 4 + 0.4 x (distance from the z axis)
# given as `--size-field axis:...` and as a .sol of those sizes at its vertices (the
# map is then linear in each input tet between them). Median of 5 each, one thread.
#   bash bench/run_size_map_bench.sh [TETS]
set -euo pipefail
cd "$(dirname "$0")/.."
tets=${1:-200000}
[ -x build/bench/bench_simplify ] || bash scripts/setup.sh
mkdir -p build/bench-data
mesh=build/bench-data/motor_${tets}.mesh
sol=build/bench-data/motor_${tets}_axis.sol
[ -f "$mesh" ] || ./build/app/tetlod generate motor --tets "$tets" -o "$mesh"
# The sizes at the vertices of the Medit file: its Vertices section, in order.
awk 'BEGIN { n = -1 }
     tolower($1) == "vertices" { getline; n = $1; print "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n" n "\n1 1"; next }
     n > 0 { printf "%.17g\n", 4 + 0.4 * sqrt($1 * $1 + $2 * $2); if (--n == 0) exit }
     END { print "End" }' "$mesh" >"$sol.tmp"
mv "$sol.tmp" "$sol"
common=(--tolerance 0.05 --stretch 0.15 --valence 25 --repeat 5)
echo "== region rule: --size 26 --size-field axis:0,0,0,0,0,1,4,0.4"
./build/bench/bench_simplify "$mesh" --size 26 --size-field axis:0,0,0,0,0,1,4,0.4 "${common[@]}"
echo "== size map: --size 26 --size-map $sol"
./build/bench/bench_simplify "$mesh" --size 26 --size-map "$sol" "${common[@]}"
