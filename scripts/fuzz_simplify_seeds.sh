#!/usr/bin/env bash
# Seeds for fuzz/fuzz_simplify: each small bundled or test .mesh behind a few sets of
# 8 threshold bytes (size, stretch, valence, tolerance, flags, field, target, crease;
# see fuzz/fuzz_simplify.cpp).
#   bash scripts/fuzz_simplify_seeds.sh DIR
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:?usage: bash scripts/fuzz_simplify_seeds.sh DIR}
mkdir -p "$dir"
meshes=(assets/box2.mesh tests/data/medit_sections.mesh tests/data/topology/checker.mesh
        tests/data/topology/edge_touch.mesh tests/data/topology/vertex_touch.mesh)
# size, stretch, valence, tolerance, flags (1 subdivide, 2 radial, 4 material, 8 target), field, target, crease
params=('\x40\x20\x15\x02\x01\x00\x00\x1e' '\xff\x05\x10\x00\x00\x00\x00\x1e'
        '\x10\x30\x19\x03\x07\x80\x00\x1e' '\x80\x20\x15\x01\x0e\x40\x30\xa0')
n=0
for mesh in "${meshes[@]}"; do
  for p in "${params[@]}"; do
    { printf "$p"; cat "$mesh"; } > "$dir/seed_$n"
    n=$((n + 1))
  done
done
echo "$n seeds in $dir"
