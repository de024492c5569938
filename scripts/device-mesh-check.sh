#!/usr/bin/env bash
# The mesh-shader path's tests (tests/test_mesh_shader.cpp: MeshShader.*, MeshPath.*, and the
# pattern layout's TessPatterns.*) on a machine whose GPU has VK_EXT_mesh_shader, from a carried
# static test binary. Build it here:
#   cmake -S . -B build-static -DLODBENCH_STATIC_RUNTIME=ON -DLODBENCH_TESTS=ON -DLODBENCH_BENCH=OFF
#   cmake --build build-static -j2 --target lodbench lodbench_tests
# and carry the tree with BUILD_DIR's lodbench, lodbench_tests, shaders/ and CMakeCache.txt (its
# object files are not needed); the machine needs a Vulkan loader (libvulkan1) and the driver.
# Prints "N passed, N failed (N skipped)" and exits non-zero when a test failed or none ran
# (about 90 s on an H200 without the validation layer).
# Usage: scripts/device-mesh-check.sh BUILD_DIR [GTEST_FILTER]
# Env: LODBENCH_VALIDATION=1 runs them under the validation layer (then VK_LAYER_PATH and, where
#      its JSON names the library without a path, LD_LIBRARY_PATH must find a carried one), whose
#      errors fail the tests.
set -uo pipefail
cd "$(dirname "$0")/.."
build=$(cd "$1" && pwd)
filter=${2:-'MeshShader.*:MeshPath.*:TessPatterns.*'}
# The binaries name the tree (configs, test data) and the SPIR-V by the paths they were built in:
# a tree carried to another folder is linked there.
src=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$build/CMakeCache.txt")
if [[ -n $src && $src != "$PWD" && ! -e $src ]]; then
  mkdir -p "$(dirname "$src")" && ln -s "$PWD" "$src"
fi
# So is the build folder, where a test finds the lodbench binary (MeshPath.* runs it).
bin=$(sed -n 's/^CMAKE_CACHEFILE_DIR:INTERNAL=//p' "$build/CMakeCache.txt")
if [[ -n $bin && $bin != "$build" && ! -e $bin/lodbench ]]; then
  mkdir -p "$bin" && ln -sf "$build/lodbench" "$bin/lodbench"
fi
export LODBENCH_SHADER_DIR=$build/shaders
[[ -f $build/COMMIT ]] && export LODBENCH_GIT_COMMIT=$(cat "$build/COMMIT")
"$build/lodbench" devices | grep -E '^\[|mesh shaders' || true
report=$(mktemp)
"$build/lodbench_tests" --gtest_filter="$filter" --gtest_output="json:$report"
rc=$?
python3 - "$report" "$rc" <<'PY'
import json, sys
runs = [t for s in json.load(open(sys.argv[1]))["testsuites"] for t in s["testsuite"]]
skipped = sum(t.get("result") == "SKIPPED" for t in runs)
failed = sum(bool(t.get("failures")) for t in runs)
passed = len(runs) - skipped - failed
print(f"{passed} passed, {failed} failed ({skipped} skipped)")
sys.exit(1 if failed or int(sys.argv[2]) != 0 or passed == 0 else 0)
PY
