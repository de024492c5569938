#!/usr/bin/env bash
# Runs the scenario library (configs/scenarios/*.json) over every scheme, one run per
# scenario under OUT (default results/scenarios), then writes each run's report.
# Usage: scripts/run-scenarios.sh [OUT] [--resolution WxH] [--only NAME[,NAME...]] [--no-images] [-- extra `run` args]
# (--no-images keeps runs small enough to ship back from a GPU machine at 1920x1080.)
# Env: LODBENCH (binary, default build/lodbench).
# A stopped sweep resumes: the same command with the same OUT keeps finished cases.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
bin=${LODBENCH:-build/lodbench}
out=results/scenarios
res=""
only=""
noImages=0
extra=()
[[ $# -gt 0 && $1 != -* ]] && { out=$1; shift; }
while [[ $# -gt 0 ]]; do
  case $1 in
    --resolution) res=$2; shift 2 ;;
    --only) only=",$2,"; shift 2 ;;
    --no-images) noImages=1; shift ;;
    --) shift; extra=("$@"); break ;;
    *) echo "run-scenarios: unknown argument $1" >&2; exit 2 ;;
  esac
done
mkdir -p "$out/configs"
start=$(date +%s)
rc=0
for cfg in configs/scenarios/*.json; do
  name=$(basename "$cfg" .json)
  [[ -n $only && $only != *",$name,"* ]] && continue
  # A copy with absolute path names (they are relative to the config) and the resolution asked for.
  copy=$out/configs/$name.json
  sed -e "s#\"\\.\\./paths/#\"$root/configs/paths/#g" "$cfg" >"$copy"
  if [[ -n $res ]]; then
    w=${res%x*} h=${res#*x}
    sed -i -e "s#\"resolution\": \\[[^]]*\\]#\"resolution\": [$w, $h]#" "$copy"
  fi
  if ((noImages)); then
    sed -i -e 's#"images": {.*}#"images": {"frames": [], "modes": []}#' "$copy"
  fi
  t0=$(date +%s)
  "$bin" run "$copy" --out "$out/$name" --quiet "${extra[@]}" >/dev/null || { r=$?; [[ $r -eq 1 ]] || exit $r; rc=1; }
  "$bin" report "$out/$name" >/dev/null || rc=1
  echo "run-scenarios: $name in $(($(date +%s) - t0)) s -> $out/$name/report/report.html"
done
# One page over every scenario run under OUT: the grid of scenarios x schemes.
"$bin" report "$out" >/dev/null || rc=1
echo "run-scenarios: summary -> $out/report/report.html"
echo "run-scenarios: done in $(($(date +%s) - start)) s (exit $rc)"
exit $rc
