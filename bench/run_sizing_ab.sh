#!/usr/bin/env bash
# Compares an earlier commit's simplifier with the working tree's under local sizing
# (docs/RESULTS.md's axis and material settings, and a radial field) on the 220k motor,
# in alternating `tetlod simplify` runs, so that the load of a shared machine falls on
# both alike. Per setting: each round's simplify phase of the two, the median of the
# ratios (new / old), and, where `perf` can count them, the instructions of one run each
# (these do not depend on the load); and whether both wrote the same mesh and history.
#   bash bench/run_sizing_ab.sh REV [ROUNDS]     # default 5 rounds
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:?usage: bash bench/run_sizing_ab.sh REV [ROUNDS]}
rounds=${2:-5}
[ -x build/app/tetlod ] || bash scripts/setup.sh
cmake --build build --target tetlod >/dev/null
old=$(bash bench/build_rev.sh "$rev")
mesh=build/bench-data/motor_200000.mesh
mkdir -p build/bench-data
[ -f "$mesh" ] || ./build/app/tetlod generate motor --tets 200000 -o "$mesh"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

settings=(
  "axis|--size 26 --size-field axis:0,0,0,0,0,1,4,0.4"
  "material|--size 26 --material-size 1=26,2=4,3=10,4=10,5=6,6=10,7=10"
  "radial|--size 20 --size-field radial:0,0,0,0.5,0.3"
)
simplify_seconds() { # BINARY NAME ARGS...
  local binary=$1 name=$2
  shift 2
  "$binary" simplify "$mesh" -o "$out/$name.mesh" --history "$out/$name.tlh" --tolerance 0.05 "$@" 2>&1 |
    sed -n -E 's/^time:.*simplify ([0-9.]+) s.*/\1/p'
}
for setting in "${settings[@]}"; do
  label=${setting%%|*}
  read -r -a args <<<"${setting#*|}"
  ratios=()
  for ((r = 1; r <= rounds; ++r)); do
    a=$(simplify_seconds "$old/build/app/tetlod" old "${args[@]}")
    b=$(simplify_seconds build/app/tetlod new "${args[@]}")
    ratios+=("$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.3f", b / a }')")
    echo "$label round $r: simplify ${a} s ($rev) -> ${b} s (working tree), ratio ${ratios[-1]}"
  done
  printf '%s\n' "${ratios[@]}" | sort -n |
    awk '{ v[NR] = $1 } END { m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2;
           printf "%s: median ratio (working tree / %s) %.3f over %d rounds\n", l, rev, m, NR }' \
      l="$label" rev="$rev"
  if cmp -s "$out/old.mesh" "$out/new.mesh" && cmp -s "$out/old.tlh" "$out/new.tlh"; then
    echo "$label: the same mesh and history"
  else
    echo "$label: output DIFFERENT"
  fi
  if command -v perf >/dev/null && perf stat -e instructions:u true >/dev/null 2>&1; then
    for b in "$old/build/app/tetlod" build/app/tetlod; do
      perf stat -x, -e instructions:u "$b" simplify "$mesh" -o "$out/x.mesh" --tolerance 0.05 \
        "${args[@]}" 2>&1 >/dev/null | awk -F, -v b="$b" -v l="$label" \
        '/instructions/ { printf "%s: instructions %.3f G, whole process: %s\n", l, $1 / 1e9, b }'
    done
  fi
done
