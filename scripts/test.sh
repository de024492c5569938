#!/usr/bin/env bash
# The test command: install what is missing, build, and run every test once under the Vulkan
# validation layer (ctest sets LODBENCH_VALIDATION=1): the tests labelled heavy (CMakeLists.txt
# says which and what covers their code under ASan instead) and those needing the Release build
# (label release: the microbenchmarks, the installed package) in a Release build, every other
# test in an ASan + UBSan build. Each test runs in one build, not both: the sanitized build is the
# stricter for the code a test reaches, and the heavy ones need Release speed.
# Set LODBENCH_SKIP_SANITIZE=1 to skip the sanitizer pass (then the Release build runs every test),
# LODBENCH_SANITIZE_ALL=1 to run the heavy tests under it too (~+20 min on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/install-report-deps.sh --cmake-follows  # the report's browser test runs in ctest when these exist
bash scripts/check-code.sh  # layers and formatting: seconds, so before the build
start=$(date +%s)
bash scripts/build.sh -DLODBENCH_TESTS=ON
release=()
[[ ${LODBENCH_SKIP_SANITIZE:-0} != 1 ]] && release=(-L 'heavy|release')
(cd build && ctest --output-on-failure -j 2 "${release[@]}")
if [[ ${LODBENCH_SKIP_SANITIZE:-0} != 1 ]]; then
  t=$(date +%s)
  # -O1 -g1: compiles faster than RelWithDebInfo's -O2 -g and keeps file:line in reports (the test
  # files at -O0 with a precompiled header: CMakeLists.txt, LODBENCH_SANITIZE_FAST_TESTS); the
  # microbenchmarks and the timing tests are not built (nothing of theirs runs here).
  label=(-LE heavy)
  [[ ${LODBENCH_SANITIZE_ALL:-0} == 1 ]] && label=()
  BUILD_DIR=build-asan BUILD_TYPE=RelWithDebInfo bash scripts/build.sh -DLODBENCH_TESTS=ON -DLODBENCH_SANITIZE=ON \
    -DLODBENCH_BENCH=OFF -DLODBENCH_TIMING_TESTS=$([[ ${#label[@]} -eq 0 ]] && echo ON || echo OFF) \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
  echo "lodbench tests: sanitizer build $(( $(date +%s) - t )) s"
  # Leak checking is off: the Vulkan loader and Mesa keep process-lifetime allocations.
  (cd build-asan && ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
     ctest --output-on-failure -j 2 "${label[@]}")
fi
echo "lodbench tests: done in $(( $(date +%s) - start )) s"
