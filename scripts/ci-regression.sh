#!/usr/bin/env bash
# CI performance-regression check: runs configs/ci.json a few times (rounds) into a temporary
# directory and compares them with the committed baseline results/baseline/ci.
# Exit 0 clean, 1 regression, 2 bad input.
# Counters are compared exactly (--require-exact: on another device or driver than the baseline's
# that is an error, exit 2, never a silent pass; a metric the baseline has and a run lacks is a
# regression). Timings: the rounds are the samples (at least 3 per side; results/baseline/ci holds
# rounds r1/ r2/ r3/, scripts/refresh-baseline.sh records them); with a one-round baseline compare
# reports ratios and says loudly that it made no timing verdict. A shared 2-core CI machine is
# noisy, so the threshold is lenient (1.0: a 2x slowdown, significant across rounds).
# Env: LODBENCH (binary, default build/lodbench), LODBENCH_CI_THRESHOLD (default 1.0),
#      LODBENCH_CI_ROUNDS (default 3), LODBENCH_CI_OUT (keep the runs and compare.{json,md} there).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${LODBENCH:-build/lodbench}
rounds=${LODBENCH_CI_ROUNDS:-3}
start=$(date +%s)
if [[ -n ${LODBENCH_CI_OUT:-} ]]; then
  out=$LODBENCH_CI_OUT
  rm -rf "$out"
else
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  out=$tmp/ci
fi
dirs=()
for ((r = 1; r <= rounds; r++)); do
  # Exit 1 = some case failed; compare reports that case as a regression, so go on.
  "$bin" run configs/ci.json --out "$out/r$r" --quiet >/dev/null || [[ $? -eq 1 ]]
  dirs+=("$out/r$r")
done
rc=0
"$bin" compare results/baseline/ci "${dirs[@]}" --require-exact --threshold "${LODBENCH_CI_THRESHOLD:-1.0}" \
  --json "$out/compare.json" --md "$out/compare.md" || rc=$?
echo "lodbench ci-regression: exit $rc in $(($(date +%s) - start)) s ($rounds rounds)"
exit $rc
