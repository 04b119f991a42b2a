#!/usr/bin/env bash
# TetLOD against the coarseners an analyst would otherwise use, on the ~200k-tet motor:
# CGAL's tetrahedral isotropic remeshing (three set-ups) and TetGen's -R coarsening.
# MMG3D is not packaged for Debian 12, so it is not here.
#   bash bench/run_compare.sh [TETS] [SIZE] [CGAL_TARGET]
# Defaults: the 200k motor, TetLOD at size 9.8 (issue 3's setting; stretch 0.15, valence
# 25, tolerance 0.05), CGAL at target edge length 6.5 (about as many tets as TetLOD's
# output). Installs libcgal-dev and tetgen (Debian packages) if missing; neither is a
# TetLOD dependency. One run of each tool: the times differ by far more than the noise.
# Times: TetLOD's pipeline (subdivide + classify + simplify, + improve) and CGAL's remeshing as the
# tools report them, without reading and writing; TetGen's whole run (it only runs whole).
set -euo pipefail
cd "$(dirname "$0")/.."
tets=${1:-200000}
size=${2:-9.8}
target=${3:-6.5}
[ -x build/bench/bench_compare ] || bash scripts/setup.sh
missing=()
[ -f /usr/include/CGAL/tetrahedral_remeshing.h ] || missing+=(libcgal-dev)
command -v tetgen > /dev/null || missing+=(tetgen)
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" != 0 ]; then
    echo "run_compare: needs the Debian packages ${missing[*]} (run as root to install them)" >&2
    exit 1
  fi
  apt-get update -q
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${missing[@]}"
fi
data=build/bench-data
out=$data/compare
mkdir -p "$out"
mesh=$data/motor_${tets}.mesh
[ -f "$mesh" ] || ./build/app/tetlod generate motor --tets "$tets" -o "$mesh"
cgal=build/bench/cgal_remesh
if [ ! -x "$cgal" ] || [ bench/compare/cgal_remesh.cpp -nt "$cgal" ]; then
  echo "compiling $cgal (CGAL is header-only: about 30 s)"
  g++ -std=c++17 -O2 -DNDEBUG bench/compare/cgal_remesh.cpp -o "$cgal" -lgmp -lmpfr
fi
now() { date +%s.%N; }
rows=()

# TetLOD.
log=$out/tetlod.log
./build/app/tetlod simplify "$mesh" -o "$out/tetlod.mesh" --size "$size" --stretch 0.15 \
  --valence 25 --tolerance 0.05 > "$log"
seconds=$(awk '/^time:/ { printf "%.2f", $3 + $6 + $9 }' "$log")
rows+=("tetlod size $size=$out/tetlod.mesh@$seconds")
# The same, then --improve (flips and vertex moves within the thresholds).
log=$out/tetlod_improve.log
./build/app/tetlod simplify "$mesh" -o "$out/tetlod_improve.mesh" --size "$size" --stretch 0.15 \
  --valence 25 --tolerance 0.05 --improve > "$log"
seconds=$(awk '/^time:/ { t = $3 + $6 + $9 } /^improve/ { i = $(NF - 1) }
  END { printf "%.2f", t + i }' "$log")
rows+=("tetlod size $size --improve=$out/tetlod_improve.mesh@$seconds")

# CGAL: its defaults; with the input's sharp edges (40 degrees, as TetLOD's crease angle)
# given as constraints, 1 and 3 iterations; and with every boundary frozen.
for setup in "default 3" "sharp=40 1" "sharp=40 3" "frozen 3"; do
  set -- $setup
  name="cgal ${1/sharp=40/sharp edges 40 deg}, $2 it."
  file=$out/cgal_${1/=/}_$2.mesh
  line=$("$cgal" "$mesh" "$file" "$target" "$2" "$1" | grep '^cgal_remesh')
  echo "$line"
  seconds=$(echo "$line" | sed -n 's/.*remesh \([0-9.]*\) s.*/\1/p')
  rows+=("$name=$file@$seconds")
done

# TetGen: -r reads the mesh, -R coarsens, -A keeps the materials.
./build/app/tetlod convert "$mesh" "$out/tg.ele" > /dev/null
for switches in rRAQ rR1/0.5AQ; do
  rm -f "$out"/tg.1.*
  start=$(now)
  if tetgen -$switches "$out/tg" > "$out/tetgen.log" 2>&1; then
    seconds=$(awk -v a="$start" -v b="$(now)" 'BEGIN { printf "%.2f", b - a }')
    kept=$out/tetgen_${switches//\//_}
    mv "$out/tg.1.node" "$kept.node"
    mv "$out/tg.1.ele" "$kept.ele"
    rows+=("tetgen -$switches=$kept.ele@$seconds")
  else
    echo "tetgen -$switches $out/tg failed (exit $?): $(tail -1 "$out/tetgen.log")"
  fi
done

echo
./build/bench/bench_compare "$mesh" --size "$size" --stretch 0.15 --valence 25 "${rows[@]}"

# Pictures of the air gap (material 2) and the magnets (5) from above, as in
# docs/RESULTS.md ("TetLOD against CGAL and TetGen").
for name in tetlod tetlod_improve cgal_default_3 cgal_sharp40_3; do
  ./build/app/tetlod render "$out/$name.mesh" -o "$out/$name.png" --materials 2,5 \
    --color material --view z --wireframe --width 420 --height 420 > /dev/null
done
echo "pictures: $out/{tetlod,tetlod_improve,cgal_default_3,cgal_sharp40_3}.png"
