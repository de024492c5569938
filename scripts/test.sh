#!/usr/bin/env bash
# The test command: install what is missing, build, run every test under the Vulkan validation
# layer (ctest sets LODBENCH_VALIDATION=1), then the same suite under ASan + UBSan.
# Set LODBENCH_SKIP_SANITIZE=1 to skip the sanitizer pass.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/install-report-deps.sh --cmake-follows  # the report's browser test runs in ctest when these exist
start=$(date +%s)
bash scripts/build.sh -DLODBENCH_TESTS=ON
(cd build && ctest --output-on-failure -j 2)
if [[ ${LODBENCH_SKIP_SANITIZE:-0} != 1 ]]; then
  BUILD_DIR=build-asan BUILD_TYPE=RelWithDebInfo bash scripts/build.sh -DLODBENCH_TESTS=ON -DLODBENCH_SANITIZE=ON
  # Leak checking is off: the Vulkan loader and Mesa keep process-lifetime allocations.
  (cd build-asan && ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
     ctest --output-on-failure -j 2)
fi
echo "lodbench tests: done in $(( $(date +%s) - start )) s"
