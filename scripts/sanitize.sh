#!/usr/bin/env bash
# The sanitizer runs that are too slow for CI (scripts/test.sh runs the core tests under
# AddressSanitizer + UndefinedBehaviorSanitizer on every change). Run after scripts/setup.sh
# (or scripts/test.sh, for the packages the interoperability tests need):
#
#   bash scripts/sanitize.sh asan   # every test (CLI, renderer, viewer too) under ASan +
#                                   # UBSan, assertions on, in build-asan-full/ (about 7 min
#                                   # to build and 6 to run on 2 cores)
#   bash scripts/sanitize.sh tsan   # the viewer's tests (its simplify and solve workers,
#                                   # under Xvfb) and the core's threaded tests under
#                                   # ThreadSanitizer, in build-tsan/ (about 10 min)
#
# Leaks are checked by scripts/test.sh (the core); here they are not: Mesa (OSMesa,
# llvmpipe, the GLX driver it unloads at exit) leaves its own allocations, which
# LeakSanitizer reports from every process that draws, some from an unloaded library
# that no suppression can name. For ThreadSanitizer, sanitizers/tsan.supp ignores races
# inside Mesa's llvmpipe driver, which is not instrumented (any race with a frame in
# it); a race between two accesses in our own code is still reported.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
case "${1:-}" in
  asan)
    cmake -S . -B build-asan-full -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTETLOD_SANITIZE=ON \
      -DTETLOD_BUILD_BENCH=OFF
    cmake --build build-asan-full -j"$jobs"
    ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 \
      UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      ctest --test-dir build-asan-full --output-on-failure -j"$jobs" --timeout 900
    ;;
  tsan)
    flags=-fsanitize=thread
    cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTETLOD_BUILD_BENCH=OFF \
      -DCMAKE_C_FLAGS=$flags -DCMAKE_CXX_FLAGS=$flags -DCMAKE_EXE_LINKER_FLAGS=$flags \
      -DCMAKE_SHARED_LINKER_FLAGS=$flags
    cmake --build build-tsan -j"$jobs" --target tetlod tetlod_viewer_tests \
      tetlod_viewer_window_tests tetlod_core_tests
    export TSAN_OPTIONS="halt_on_error=1 suppressions=$PWD/scripts/sanitizers/tsan.supp"
    build-tsan/tests/tetlod_core_tests \
      --gtest_filter='SimplifyPastValence.*:SimplifyCancel.*:IoAtomicWrite.*'
    build-tsan/tests/tetlod_viewer_tests
    xvfb-run -a -s "-screen 0 1280x1024x24" build-tsan/tests/tetlod_viewer_window_tests
    ;;
  *)
    echo "usage: bash scripts/sanitize.sh asan|tsan" >&2
    exit 2
    ;;
esac
