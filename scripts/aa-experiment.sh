#!/usr/bin/env bash
# A/A experiment: the false-alarm rate of `lodbench compare` at its default settings (threshold
# 0.10, alpha 0.01, 3 rounds a side). The same binary runs a tiny config (2 cases, 96x54, 40
# frames, lavapipe) as both sides, rounds interleaved A B B A A B as `ab` does; every flagged
# regression or improvement is a false alarm. For contrast it also applies the old rule (frames of
# one round a side as samples: Mann-Whitney p < alpha and ratio beyond the threshold) to round 1
# of each side. A benchmark, not a test: it prints figures, it passes nothing.
# Usage: bash scripts/aa-experiment.sh [COMPARISONS=20] [OUT=/tmp/lodbench-aa]
# Env: LODBENCH (binary, default build/lodbench).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${LODBENCH:-build/lodbench}
n=${1:-20}
out=${2:-/tmp/lodbench-aa}
[[ -n ${AA_ANALYZE_ONLY:-} ]] || rm -rf "$out"
mkdir -p "$out"
cat >"$out/aa.json" <<JSON
{"name": "aa", "resolution": [96, 54], "grid": 8, "fps": 30, "warmup_frames": 3, "max_frames": 40,
 "terrain": {"type": "procedural", "size": 129, "seed": 1},
 "paths": ["$PWD/configs/paths/flyover.csv"],
 "schemes": [{"name": "uniform", "params": {"level": 8}}, {"name": "sphere", "params": {"tri_size": 3}}]}
JSON
start=$(date +%s)
for ((k = 1; k <= n; k++)); do
  [[ -n ${AA_ANALYZE_ONLY:-} ]] && break  # re-analyse the runs already in OUT
  d=$out/c$k
  for side in a1 b1 b2 a2 a3 b3; do  # interleaved, so slow drifts fall on both sides alike
    "$bin" run "$out/aa.json" --out "$d/${side:0:1}/r${side:1}" --quiet >/dev/null 2>&1
  done
  "$bin" compare "$d/a" "$d/b" --json "$d/compare.json" >/dev/null 2>&1 || true
done
python3 - "$out" "$n" <<'PY'
import json, sys, glob, statistics, math

def mannwhitneyu_p(x, y):  # two-sided, normal approximation with tie and continuity correction
    allv = sorted([(v, 0) for v in x] + [(v, 1) for v in y])
    n1, n2 = len(x), len(y); n = n1 + n2
    ranks_x = 0.0; tie = 0.0; i = 0
    while i < n:
        j = i
        while j < n and allv[j][0] == allv[i][0]: j += 1
        r = (i + 1 + j) / 2.0; t = j - i; tie += t ** 3 - t
        ranks_x += r * sum(1 for k in range(i, j) if allv[k][1] == 0)
        i = j
    u = ranks_x - n1 * (n1 + 1) / 2.0
    u = max(u, n1 * n2 - u)
    var = n1 * n2 / 12.0 * ((n + 1) - tie / (n * (n - 1)))
    if var <= 0: return 1.0
    z = (u - n1 * n2 / 2.0 - 0.5) / math.sqrt(var)
    return min(1.0, math.erfc(z / math.sqrt(2)))
out, n = sys.argv[1], int(sys.argv[2])
cases = flagged = comps = 0
old_cases = old_flagged = old_comps = 0
ps, ratios = [], []
for k in range(1, n + 1):
    v = json.load(open(f"{out}/c{k}/compare.json"))
    hit = False
    for c in v["cases"]:
        t = c["timing"]
        cases += 1
        ps.append(t.get("p", 1.0)); ratios.append(t.get("ratio", 0))
        if t["verdict"] in ("regression", "improvement"):
            flagged += 1; hit = True
    comps += hit
    old_hit = False
    for f in sorted(glob.glob(f"{out}/c{k}/a/r1/cases/*.json")):
        a = [x["gpu_ms"] for x in json.load(open(f))["frames"]]
        b = [x["gpu_ms"] for x in json.load(open(f.replace("/a/r1/", "/b/r1/")))["frames"]]
        ratio = statistics.median(b) / statistics.median(a)
        p = mannwhitneyu_p(a, b)
        old_cases += 1
        if p < 0.01 and (ratio > 1.1 or ratio < 1 / 1.1):
            old_flagged += 1; old_hit = True
    old_comps += old_hit
print(f"A/A on lavapipe: {n} comparisons x {cases // n} cases, 3 rounds a side, threshold 0.10, alpha 0.01")
print(f"  rounds rule (default):  {flagged}/{cases} case verdicts flagged, {comps}/{n} comparisons with a false alarm")
print(f"  old frames-as-samples:  {old_flagged}/{old_cases} case verdicts flagged, {old_comps}/{n} comparisons with a false alarm")
print(f"  round-rule p: min {min(ps):.3g}, median {statistics.median(ps):.3g}; ratio range [{min(ratios):.3f}, {max(ratios):.3f}]")
PY
echo "aa-experiment: $(($(date +%s) - start)) s, runs in $out"
