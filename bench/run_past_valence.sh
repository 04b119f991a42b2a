#!/usr/bin/env bash
# Subdivision past the valence on the bundled coarse motor (assets/motor.mesh, tets up
# to 20.4 mm, nodes of up to 37 neighbours): for each size, the run within the valence
# (--within-valence) against the default (a run past it where tets stay above the
# size). Prints a Markdown table: tets above the size and tets of each, what the runs
# past the valence did, and the wall time of each command (one run each); for the
# default also with --one-thread (the run past the valence after the first instead of
# alongside it on a second thread: the same output, checked here).
#   bash bench/run_past_valence.sh [SIZES...]     (default: 8 10 12 14 16 18 20)
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/app/tetlod ] || bash scripts/setup.sh
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(8 10 12 14 16 18 20)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
above() { grep -oE 'breaking a threshold: [0-9]+ tets? below the stretch, [0-9]+ above' <<<"$1" |
  grep -oE '[0-9]+ above' | cut -d' ' -f1; }
tets() { grep -E '^whole mesh' <<<"$1" | tail -1 | awk '{print $5}'; }
wall() { # wall LOG_FILE: the seconds /usr/bin/time wrote
  sed -n 's/^WALL //p' "$1"; }
echo "| size | within: above the size | tets | s | default: above the size | tets | s | s, --one-thread | runs past the valence |"
echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"
for s in "${sizes[@]}"; do
  /usr/bin/time -f "WALL %e" -o "$out/w.time" ./build/app/tetlod simplify assets/motor.mesh \
    -o "$out/w.mesh" --size "$s" --tolerance 0.05 --within-valence >"$out/w.log" 2>&1
  /usr/bin/time -f "WALL %e" -o "$out/d.time" ./build/app/tetlod simplify assets/motor.mesh \
    -o "$out/d.mesh" --size "$s" --tolerance 0.05 >"$out/d.log" 2>&1
  /usr/bin/time -f "WALL %e" -o "$out/o.time" ./build/app/tetlod simplify assets/motor.mesh \
    -o "$out/o.mesh" --size "$s" --tolerance 0.05 --one-thread >"$out/o.log" 2>&1
  cmp -s "$out/d.mesh" "$out/o.mesh" || { echo "size $s: --one-thread wrote another mesh" >&2; exit 1; }
  w=$(cat "$out/w.log")
  d=$(cat "$out/d.log")
  past=$(sed -n 's/^past the valence: subdivision within the valence threshold left [0-9]* tets above the size; //p' <<<"$d")
  echo "| $s | $(above "$w") | $(tets "$w") | $(wall "$out/w.time") | $(above "$d") | $(tets "$d") | $(wall "$out/d.time") | $(wall "$out/o.time") | ${past:-none made} |"
done
