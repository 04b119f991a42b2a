#!/usr/bin/env bash
# Whether the working tree's simplifier writes the same meshes and histories, byte for
# byte, as an earlier commit's, on seven settings: the 220k motor at sizes 9.8 and 12,
# with its axis size field and with material sizes (Table I), the spheres with a radial
# field, the bundled motor at 8, and box2. For changes meant to be pure speed-ups.
#   bash bench/check_same_output.sh REV
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:?usage: bash bench/check_same_output.sh REV}
[ -x build/app/tetlod ] || bash scripts/setup.sh
cmake --build build --target tetlod >/dev/null
old=$(bash bench/build_rev.sh "$rev")
mesh=build/bench-data/motor_200000.mesh
[ -f "$mesh" ] || { mkdir -p build/bench-data; ./build/app/tetlod generate motor --tets 200000 -o "$mesh"; }
t="--tolerance 0.05 --stretch 0.15 --valence 25"
settings=(
  "u98|$mesh --size 9.8 $t"
  "u12|$mesh --size 12 $t"
  "axis|$mesh --size 26 --size-field axis:0,0,0,0,0,1,4,0.4 $t"
  "material|$mesh --size 26 --material-size 1=26,2=4,3=10,4=10,5=6,6=10,7=10 $t"
  "spheres|assets/spheres.mesh --size 30 --size-field radial:0,0,0,2,0.3 $t"
  "motor8|assets/motor.mesh --size 8 $t"
  "box2|assets/box2.mesh --size 10 $t")
out=build/ab/same_output
rm -rf "$out"
mkdir -p "$out"
different=0
for s in "${settings[@]}"; do
  name=${s%%|*}
  read -r -a args <<<"${s#*|}"
  "$old/build/app/tetlod" simplify "${args[@]}" -o "$out/$name.old.mesh" --history "$out/$name.old.tlh" >/dev/null
  ./build/app/tetlod simplify "${args[@]}" -o "$out/$name.new.mesh" --history "$out/$name.new.tlh" >/dev/null
  if cmp -s "$out/$name.old.mesh" "$out/$name.new.mesh" && cmp -s "$out/$name.old.tlh" "$out/$name.new.tlh"; then
    echo "$name: the same mesh and history"
  else
    echo "$name: DIFFERENT ($out/$name.*)"
    different=1
  fi
done
exit $different
