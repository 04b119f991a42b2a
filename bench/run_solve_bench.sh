#!/usr/bin/env bash
# Speed of the electrostatic solve (issue 6 targets: 100k tets <= 1 s, 1M tets <= 15 s).
#   bash bench/run_solve_bench.sh [REPEAT]
# 1. the bundled spheres capacitor refined 1:8 once and twice (129k, 1.03M tets);
# 2. the same with the box boundary grounded and material 4 a dielectric (more unknowns);
# 3. motors of ~100k and ~1.1M tets (generated once, cached in build/bench-data), the
#    shaft at 1 and the outer boundary grounded: most nodes are unknowns.
set -euo pipefail
cd "$(dirname "$0")/.."
repeat=${1:-5}
[ -x build/bench/bench_solve ] || bash scripts/setup.sh
mkdir -p build/bench-data
for tets in 100000 1000000; do
  mesh=build/bench-data/motor_${tets}.mesh
  [ -f "$mesh" ] || ./build/app/tetlod generate motor --tets "$tets" -o "$mesh"
done
echo "## spheres capacitor (material 1 at 1, material 4 grounded)"
./build/bench/bench_solve --repeat "$repeat" --levels 2
echo "## spheres, box boundary grounded"
./build/bench/bench_solve --repeat "$repeat" --levels 2 --box
for tets in 100000 1000000; do
  echo "## motor_${tets}: shaft (3) at 1, boundary grounded"
  ./build/bench/bench_solve --repeat "$repeat" --levels 0 --conductor 3 --ground boundary \
    "build/bench-data/motor_${tets}.mesh"
done
