#!/usr/bin/env bash
# Scrubs the whole collapse history of the ~200k-tet motor in the real viewer window
# under Xvfb (software OpenGL: llvmpipe) and prints frame times.
#   bash bench/run_view_bench.sh [TETS] [WxH] [FRAMES] [SCALE]
# SCALE: resolution of the 3D view while it moves (--interactive-scale, default 0.5).
# The script simplifies (size 12, tolerance 0.05), then drags the LOD slider from
# the finest to the coarsest level over FRAMES frames and back, like a hand on the
# slider, and writes per-frame times to build/bench-data/view_scrub_TETS_WxH.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
tets=${1:-200000}
size=${2:-1280x800}
frames=${3:-120}
scale=${4:-0.5}
[ -x build/app/tetlod ] || bash scripts/setup.sh
mkdir -p build/bench-data
mesh=build/bench-data/motor_${tets}.mesh
[ -f "$mesh" ] || ./build/app/tetlod generate motor --tets "$tets" -o "$mesh"
script=build/bench-data/view_scrub.script
cat >"$script" <<SCRIPT
thresholds size=12 stretch=0.15 valence=25 tolerance=0.05
simplify
bench-scrub frames=$frames out=build/bench-data/view_scrub_${tets}_${size}.csv
quit
SCRIPT
xvfb-run -a -s "-screen 0 1920x1200x24" ./build/app/tetlod view "$mesh" --hide 1 --size "$size" \
  --interactive-scale "$scale" --script "$script"
