#!/usr/bin/env bash
# Re-records the CI baseline results/baseline/ci (rounds r1/ r2/ r3/) on purpose: after an intended change of counters
# or timings, a scheme added to configs/ci.json, or a new Mesa/lavapipe. Run it from a clean,
# committed tree (the baseline records the git commit), then review and commit:
#   bash scripts/refresh-baseline.sh && git add results/baseline/ci && git commit -m "baseline: <why>"
# --add: only the cases configs/ci.json has and the baseline lacks (a scheme added to the registry
# joins "all"): each round is resumed in place, so every recorded case stays byte for byte and only
# the new ones run (README.md, "Adding a scheme").
# Env: LODBENCH (binary, default build/lodbench).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${LODBENCH:-build/lodbench}
rounds=${LODBENCH_BASELINE_ROUNDS:-3}  # compare judges timing from rounds: at least 3 per side
if [[ ${1:-} == --add ]]; then
  for ((r = 1; r <= rounds; r++)); do
    [[ -d results/baseline/ci/r$r ]] || { echo "refresh-baseline: no results/baseline/ci/r$r to add to" >&2; exit 2; }
    "$bin" run configs/ci.json --out "results/baseline/ci/r$r" --quiet >/dev/null
    "$bin" gbench "results/baseline/ci/r$r" >/dev/null
    rm -rf "results/baseline/ci/r$r/images" "results/baseline/ci/r$r/truth"
  done
  "$bin" compare results/baseline/ci results/baseline/ci --require-exact >/dev/null
  echo "lodbench: added the new cases of configs/ci.json to results/baseline/ci ($rounds rounds); git status results/baseline/ci"
  exit 0
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for ((r = 1; r <= rounds; r++)); do
  "$bin" run configs/ci.json --out "$tmp/ci/r$r" --quiet >/dev/null
  "$bin" gbench "$tmp/ci/r$r" >/dev/null
  # Images (none in this config) and the ray-cast cache are not results a comparison reads.
  rm -rf "$tmp/ci/r$r/images" "$tmp/ci/r$r/truth"
done
"$bin" compare "$tmp/ci" "$tmp/ci" --require-exact >/dev/null  # reads back cleanly (exit 0) before it replaces anything
rm -rf results/baseline/ci
mkdir -p results/baseline
mv "$tmp/ci" results/baseline/ci
echo "lodbench: new baseline results/baseline/ci ($rounds rounds, $(du -sh results/baseline/ci | cut -f1)) from commit $(git rev-parse --short HEAD)"
