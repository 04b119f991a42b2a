#!/usr/bin/env bash
# Whether the working tree's simplifier writes the same meshes and histories, byte for
# byte, as an earlier commit's (histories in another file format: the same levels).
# For changes meant to be pure speed-ups.
#   bash bench/check_same_output.sh REV                 # seven settings
#   bash bench/check_same_output.sh REV past-valence    # runs past the valence
# The seven settings: the 220k motor at sizes 9.8 and 12, with its axis size field and
# with material sizes (Table I), the spheres with a radial field, the bundled motor at
# 8, and box2. The runs past the valence (red levels, bisection, edge removals): the
# bundled motor (tets up to 20.4 mm) at sizes 4 to 18, with valence 20 and with
# material sizes, and the spheres at 0.3 and 0.2, also comparing what the report says
# of the run past the valence (where it is not the result); mesh files given in
# TETLOD_EXTRA="FILE:SIZE ..." are run too.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:?usage: bash bench/check_same_output.sh REV [past-valence]}
set_name=${2:-seven}
[ -x build/app/tetlod ] || bash scripts/setup.sh
cmake --build build --target tetlod >/dev/null
old=$(bash bench/build_rev.sh "$rev")
t="--tolerance 0.05 --stretch 0.15 --valence 25"
if [ "$set_name" = past-valence ]; then
  m=assets/motor.mesh
  settings=(
    "m4|$m --size 4 $t" "m6|$m --size 6 $t" "m7|$m --size 7 $t" "m8|$m --size 8 $t"
    "m10|$m --size 10 $t" "m14|$m --size 14 $t" "m18|$m --size 18 $t"
    "m12v20|$m --size 12 --tolerance 0.05 --valence 20" "m17v20|$m --size 17 --tolerance 0.05 --valence 20"
    "mmat|$m --size 16 --material-size 1=6,2=16,3=10 $t"
    "s03|assets/spheres.mesh --size 0.3 --tolerance 0.02"
    "s02v18|assets/spheres.mesh --size 0.2 --valence 18 --tolerance 0.02")
  k=0
  for extra in ${TETLOD_EXTRA:-}; do
    settings+=("extra$k|${extra%:*} --size ${extra##*:}")
    k=$((k + 1))
  done
else
  mesh=build/bench-data/motor_200000.mesh
  [ -f "$mesh" ] || { mkdir -p build/bench-data; ./build/app/tetlod generate motor --tets 200000 -o "$mesh"; }
  settings=(
    "u98|$mesh --size 9.8 $t"
    "u12|$mesh --size 12 $t"
    "axis|$mesh --size 26 --size-field axis:0,0,0,0,0,1,4,0.4 $t"
    "material|$mesh --size 26 --material-size 1=26,2=4,3=10,4=10,5=6,6=10,7=10 $t"
    "spheres|assets/spheres.mesh --size 30 --size-field radial:0,0,0,2,0.3 $t"
    "motor8|assets/motor.mesh --size 8 $t"
    "box2|assets/box2.mesh --size 10 $t")
fi
out=build/ab/same_output
rm -rf "$out"
mkdir -p "$out"
different=0
# Histories of another file format (an older REV writes format 1 or 2, with no
# checksum) are compared by their levels: step 0, a third, two thirds and the last,
# each written from both by this build's `tetlod lod`.
same_levels() { # OLD.tlh NEW.tlh NEW.log
  local last k
  last=$(grep -oE '\(step [0-9]+ of [0-9]+\)' "$3" | head -1 | grep -oE '[0-9]+\)' | tr -d ')')
  [ -n "$last" ] || return 1
  for k in 0 $((last / 3)) $((2 * last / 3)) "$last"; do
    ./build/app/tetlod lod "$1" --step "$k" -o "$out/level.old.mesh" >/dev/null 2>&1 || return 1
    ./build/app/tetlod lod "$2" --step "$k" -o "$out/level.new.mesh" >/dev/null 2>&1 || return 1
    cmp -s "$out/level.old.mesh" "$out/level.new.mesh" || return 1
  done
}
for s in "${settings[@]}"; do
  name=${s%%|*}
  read -r -a args <<<"${s#*|}"
  for side in old new; do
    bin=./build/app/tetlod
    [ "$side" = old ] && bin=$old/build/app/tetlod
    "$bin" simplify "${args[@]}" -o "$out/$name.$side.mesh" --history "$out/$name.$side.tlh" \
      >"$out/$name.$side.log" 2>&1
    # What the report says of a run past the valence (the result or not), times aside.
    grep '^past the valence' "$out/$name.$side.log" >"$out/$name.$side.past" || true
  done
  red=$(grep -oE 'in [0-9]+ red levels?' "$out/$name.new.log" | head -1 || true)
  history=""
  if ! cmp -s "$out/$name.old.tlh" "$out/$name.new.tlh"; then
    history="different file"
    same_levels "$out/$name.old.tlh" "$out/$name.new.tlh" "$out/$name.new.log" &&
      history="other file format, the same levels"
  fi
  if cmp -s "$out/$name.old.mesh" "$out/$name.new.mesh" && [ "$history" != "different file" ] &&
    cmp -s "$out/$name.old.past" "$out/$name.new.past"; then
    echo "$name: the same mesh and history${red:+ ($red)}${history:+ ($history)}"
  else
    echo "$name: DIFFERENT ($out/$name.*)"
    different=1
  fi
done
exit $different
