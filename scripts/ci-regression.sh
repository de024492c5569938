#!/usr/bin/env bash
# CI performance-regression check: runs configs/ci.json into a temporary directory and compares it
# with the committed baseline results/baseline/ci. Exit 0 clean, 1 regression, 2 bad input.
# Counters are compared exactly (when device and driver match the baseline's); timings with a
# lenient threshold, since a shared 2-core CI machine is noisy and the baseline was recorded on
# another machine: 1.0 flags only a significant 2x slowdown.
# Env: LODBENCH (binary, default build/lodbench), LODBENCH_CI_THRESHOLD (default 1.0),
#      LODBENCH_CI_OUT (keep the run and its compare.{json,md} there instead of a temp dir).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${LODBENCH:-build/lodbench}
start=$(date +%s)
if [[ -n ${LODBENCH_CI_OUT:-} ]]; then
  out=$LODBENCH_CI_OUT
  rm -rf "$out"
else
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  out=$tmp/ci
fi
# Exit 1 = some case failed; compare reports that case as a regression, so go on.
"$bin" run configs/ci.json --out "$out" --quiet >/dev/null || [[ $? -eq 1 ]]
rc=0
"$bin" compare results/baseline/ci "$out" --threshold "${LODBENCH_CI_THRESHOLD:-1.0}" \
  --json "$out/compare.json" --md "$out/compare.md" || rc=$?
echo "lodbench ci-regression: exit $rc in $(($(date +%s) - start)) s"
exit $rc
