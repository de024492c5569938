#!/usr/bin/env bash
# The main job: install what is missing, build, run configs/quick.json on lavapipe (every scheme,
# a small sweep of each one's main parameter), write the report and print its path once.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/install-report-deps.sh --cmake-follows
bash scripts/build.sh -DLODBENCH_TESTS=OFF
start=$(date +%s)
# A failed case still leaves a run (exit 1): report it, then pass the status on.
rc=0
run=$(./build/lodbench run configs/quick.json "$@" | tail -n 1) || rc=$?
[[ -n $run && -f $run/run.json ]] || exit $((rc ? rc : 1))
# `lodbench report` prints the page's path on stdout (nothing when it could not render HTML).
page=$(./build/lodbench report "$run") || rc=$?
echo "lodbench: main job done in $(($(date +%s) - start)) s after the build" >&2
echo "lodbench: report: ${page:-$run/report/report.md}"
exit $rc
