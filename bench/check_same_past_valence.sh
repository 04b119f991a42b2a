#!/usr/bin/env bash
# Whether the working tree's runs past the valence (red levels, bisection, edge
# removals) write the same meshes and histories, byte for byte, and report the same
# runs past the valence, as an earlier commit's: the bundled motor (tets up to 20.4 mm) at sizes from 4 to 18, with a lower
# valence threshold and with material sizes, and the spheres at two sizes. Any further
# mesh files given in TETLOD_EXTRA="FILE:SIZE ..." are run too. For changes to
# subdivision meant to be pure speed-ups; bench/check_same_output.sh covers the rest.
#   bash bench/check_same_past_valence.sh REV
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:?usage: bash bench/check_same_past_valence.sh REV}
[ -x build/app/tetlod ] || bash scripts/setup.sh
cmake --build build --target tetlod >/dev/null
old=$(bash bench/build_rev.sh "$rev")
m=assets/motor.mesh
t="--tolerance 0.05"
settings=(
  "m4|$m --size 4 $t" "m6|$m --size 6 $t" "m7|$m --size 7 $t" "m8|$m --size 8 $t"
  "m10|$m --size 10 $t" "m14|$m --size 14 $t" "m18|$m --size 18 $t"
  "m12v20|$m --size 12 --valence 20 $t" "m17v20|$m --size 17 --valence 20 $t"
  "mmat|$m --size 16 --material-size 1=6,2=16,3=10 $t"
  "s03|assets/spheres.mesh --size 0.3 --tolerance 0.02"
  "s02v18|assets/spheres.mesh --size 0.2 --valence 18 --tolerance 0.02")
k=0
for extra in ${TETLOD_EXTRA:-}; do
  settings+=("extra$k|${extra%:*} --size ${extra##*:}")
  k=$((k + 1))
done
out=build/ab/same_past_valence
rm -rf "$out"
mkdir -p "$out"
different=0
for s in "${settings[@]}"; do
  name=${s%%|*}
  read -r -a args <<<"${s#*|}"
  "$old/build/app/tetlod" simplify "${args[@]}" -o "$out/$name.old.mesh" --history "$out/$name.old.tlh" >"$out/$name.old.log" 2>&1
  ./build/app/tetlod simplify "${args[@]}" -o "$out/$name.new.mesh" --history "$out/$name.new.tlh" >"$out/$name.new.log" 2>&1
  past=$(grep -oE 'in [0-9]+ red levels?' "$out/$name.new.log" | head -1 || true)
  # Where the run past the valence is not the result, its report line says what it did.
  grep '^past the valence' "$out/$name.old.log" >"$out/$name.old.past" || true
  grep '^past the valence' "$out/$name.new.log" >"$out/$name.new.past" || true
  if cmp -s "$out/$name.old.mesh" "$out/$name.new.mesh" && cmp -s "$out/$name.old.tlh" "$out/$name.new.tlh" &&
    cmp -s "$out/$name.old.past" "$out/$name.new.past"; then
    echo "$name: the same mesh and history (${past:-no red level})"
  else
    echo "$name: DIFFERENT ($out/$name.*)"
    different=1
  fi
done
exit $different
