#!/usr/bin/env bash
# Far moves of the level in the real viewer window under Xvfb: the ~1M-tet motor's
# collapse history from its coarsest level to its finest and back (`scrub` in a script,
# which waits until the level is drawn and its statistics computed), timed by the
# screenshots taken in between.
#   bash bench/run_view_jump_bench.sh [TETS] [SIZE] [TETLOD]
# TETLOD: the binary to time (default build/app/tetlod; e.g. an earlier build from
# bench/build_rev.sh, to compare).
set -euo pipefail
cd "$(dirname "$0")/.."
tets=${1:-1000000}
size=${2:-7.7}
tetlod=${3:-build/app/tetlod}
[ -x build/app/tetlod ] || bash scripts/setup.sh
mkdir -p build/bench-data
mesh=build/bench-data/motor_${tets}.mesh
[ -f "$mesh" ] || ./build/app/tetlod generate motor --tets "$tets" -o "$mesh"
history=build/bench-data/motor_${tets}_${size}.tlh
[ -f "$history" ] || ./build/app/tetlod simplify "$mesh" -o build/bench-data/jump_level.mesh \
  --size "$size" --tolerance 0.18 --history "$history" >/dev/null
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cat >"$dir/jump.script" <<SCRIPT
scrub end
screenshot $dir/0.png width=64 height=64
scrub step=0
screenshot $dir/1.png width=64 height=64
scrub end
screenshot $dir/2.png width=64 height=64
quit
SCRIPT
xvfb-run -a -s "-screen 0 1920x1200x24" "$tetlod" view "$history" --size 1280x800 \
  --script "$dir/jump.script" >/dev/null 2>&1
t0=$(stat -c %.3Y "$dir/0.png")
t1=$(stat -c %.3Y "$dir/1.png")
t2=$(stat -c %.3Y "$dir/2.png")
awk -v a="$t0" -v b="$t1" -v c="$t2" -v h="$history" 'BEGIN {
  printf "%s: coarsest -> finest %.2f s, finest -> coarsest %.2f s\n", h, b - a, c - b }'
