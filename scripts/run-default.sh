#!/usr/bin/env bash
# The main job: install what is missing, build, run configs/quick.json on lavapipe.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh -DLODBENCH_TESTS=OFF
./build/lodbench run configs/quick.json "$@"
