#!/usr/bin/env bash
# Builds `tetlod` and `bench_simplify` of an earlier commit in a worktree under build/ab/
# (once; kept for later calls) and prints that worktree's path.
#   old=$(bash bench/build_rev.sh REV)   # then $old/build/app/tetlod, $old/build/bench/...
set -euo pipefail
cd "$(dirname "$0")/.."
commit=$(git rev-parse --verify "${1:?usage: bash bench/build_rev.sh REV}^{commit}")
old=build/ab/${commit:0:12}
if [ ! -x "$old/build/bench/bench_simplify" ]; then
  rm -rf "$old"
  git worktree prune
  git worktree add --detach "$old" "$commit" >/dev/null
  cmake -S "$old" -B "$old/build" -DCMAKE_BUILD_TYPE=Release -DTETLOD_BUILD_TESTS=OFF >/dev/null
  cmake --build "$old/build" -j"$(nproc)" --target bench_simplify tetlod >/dev/null
fi
echo "$old"
