#!/usr/bin/env bash
# Reproduces the paper's Table I on the ~200k-tet bundled motor: the input and four
# simplifications (uniform size at two settings, region-based and material-based
# sizing), with thresholds stretch 0.15 and valence 25 as in the paper.
# Prints a Markdown table (thresholds in brackets, as the paper prints them).
#   bash bench/table1.sh [TETS]
set -euo pipefail
cd "$(dirname "$0")/.."
tets=${1:-200000}
[ -x build/app/tetlod ] || bash scripts/setup.sh
mkdir -p build/bench-data build/table1
mesh=build/bench-data/motor_${tets}.mesh
[ -f "$mesh" ] || ./build/app/tetlod generate motor --tets "$tets" -o "$mesh" >/dev/null

common="--stretch 0.15 --valence 25 --tolerance 0.05"
names=("uniform 9.8" "uniform 19.7" "region" "material")
flags=("--size 9.8"
  "--size 19.7"
  "--size 26 --size-field axis:0,0,0,0,0,1,4,0.4"
  "--size 26 --material-size 1=26,2=4,3=10,4=10,5=6,6=10,7=10")
sizes=("9.8" "19.7" "26" "26")

field() { # field NAME JSON_LINE
  sed -E "s/.*\"$1\": ([^,}]*).*/\1/" <<<"$2"
}
row() { # row LABEL FILE SIZE_BRACKET EXTRA
  local whole
  whole=$(./build/app/tetlod stats --json "$2" | grep '"whole"')
  printf "| %s | %s | %s | %s | %.2f | %.3f%s | %s%s | %.2f%s | %s |\n" "$1" \
    "$(field nodes "$whole")" "$(field edges "$whole")" "$(field elements "$whole")" \
    "$(field average_stretch "$whole")" "$(field min_stretch "$whole")" "${3:+ (0.15)}" \
    "$(field max_valence "$whole")" "${3:+ (25)}" "$(field max_size "$whole")" "${3:+ ($3)}" "$4"
}

echo "| mesh | #nodes | #edges | #elements | ave. stretch | min. stretch | max. valence | max. size | over a threshold / time |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"
row "input (TetGen, $tets target)" "$mesh" "" ""
for k in "${!names[@]}"; do
  out=build/table1/motor_${k}.mesh
  log=$(./build/app/tetlod simplify "$mesh" -o "$out" $common ${flags[$k]})
  viol=$(grep "breaking a threshold" <<<"$log" | sed -E 's/.*threshold: //')
  time=$(grep "^time:" <<<"$log" | sed -E 's/time: //')
  row "${names[$k]}" "$out" "${sizes[$k]}" "$viol; $time"
done
