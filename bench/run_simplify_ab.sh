#!/usr/bin/env bash
# Compares the simplifier of an earlier commit with the working tree on the same mesh,
# in alternating runs, so that the load of a shared machine falls on both alike.
# Prints each pair's simplify-phase medians, the median of their ratios (new / old)
# and, where `perf` can count them, instructions and branch misses of one run each
# (these do not depend on the load). Also checks that both give the same output
# (bench/check_same_output.sh).
#   bash bench/run_simplify_ab.sh REV [ROUNDS] [TETS] [SIZE]     # defaults 5 200000 9.8
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:?usage: bash bench/run_simplify_ab.sh REV [ROUNDS] [TETS] [SIZE]}
rounds=${2:-5}
tets=${3:-200000}
size=${4:-9.8}
[ -x build/bench/bench_simplify ] || bash scripts/setup.sh
cmake --build build --target bench_simplify tetlod >/dev/null

# The old build: a worktree of REV.
old=$(bash bench/build_rev.sh "$rev")

mkdir -p build/bench-data
mesh=build/bench-data/motor_${tets}.mesh
[ -f "$mesh" ] || ./build/app/tetlod generate motor --tets "$tets" -o "$mesh"
args=("$mesh" --size "$size" --tolerance 0.05 --stretch 0.15 --valence 25)

# The same output, byte for byte (meshes and histories, seven settings).
bash bench/check_same_output.sh "$rev" || echo "output: DIFFERENT (see above)"

simplify_median() { # BINARY
  "$1" "${args[@]}" --repeat 3 | sed -n -E 's/^median of .*simplify ([0-9.]+)\).*/\1/p'
}
ratios=()
for ((r = 1; r <= rounds; ++r)); do
  a=$(simplify_median "$old/build/bench/bench_simplify")
  b=$(simplify_median build/bench/bench_simplify)
  ratios+=("$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.3f", b / a }')")
  echo "round $r: simplify ${a} s (${rev}) -> ${b} s (working tree), ratio ${ratios[-1]}"
done
printf '%s\n' "${ratios[@]}" | sort -n |
  awk '{ v[NR] = $1 } END { m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2;
         printf "median ratio (working tree / %s): %.3f over %d rounds\n", rev, m, NR }' rev="$rev"

if command -v perf >/dev/null && perf stat -e instructions:u true >/dev/null 2>&1; then
  for b in "$old/build/bench/bench_simplify" build/bench/bench_simplify; do
    perf stat -x, -e instructions:u,branch-misses:u "$b" "${args[@]}" --repeat 1 2>&1 >/dev/null |
      awk -F, -v b="$b" '{ printf "%s %.3f G, ", $3, $1 / 1e9 } END { print "whole process: " b }'
  done
fi
