#!/usr/bin/env bash
# The main job: install what is missing, build, run configs/quick.json on lavapipe, write the
# report and print its path.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/install-report-deps.sh
bash scripts/build.sh -DLODBENCH_TESTS=OFF
# A failed case still leaves a run (exit 1): report it, then pass the status on.
rc=0
run=$(./build/lodbench run configs/quick.json "$@" | tail -n 1) || rc=$?
[[ -n $run && -f $run/run.json ]] || exit $((rc ? rc : 1))
./build/lodbench report "$run" >&2
echo "lodbench: report: $run/report/report.html"
exit $rc
