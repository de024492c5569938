#!/usr/bin/env bash
# Runs the published real-GPU sweeps on a machine with an NVIDIA GPU from a carried static build
# (-DLODBENCH_STATIC_RUNTIME=ON) and packs them into OUT_DIR/results.tar.gz.
# Usage: scripts/device-publish.sh BUILD_DIR OUT_DIR CONFIG...
# Env: DEADLINE_S (default 540): seconds from the start after which a running sweep is stopped with
# SIGINT (it keeps its finished cases and can be resumed with the same --out), so the results are
# still packed inside the device machine's per-command limit.
# The GPU idles at a low clock: a few seconds of load first, and the clock is recorded before and after.
set -euo pipefail
build=$1 out=$2
shift 2
export LODBENCH_SHADER_DIR=$build/shaders
# The carried tree's .git may be stale: the commit the build was made from travels as BUILD_DIR/COMMIT.
[[ -f $build/COMMIT ]] && export LODBENCH_GIT_COMMIT=$(cat "$build/COMMIT")
work=$(mktemp -d)
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv | tee "$work/gpu.txt"
"$build/lodbench" devices | tee -a "$work/gpu.txt"
start=$(date +%s)
while (( $(date +%s) - start < 8 )); do
  "$build/lodbench" run configs/gpu-measure-off.json --out "$work/warmup" -q >/dev/null; rm -rf "$work/warmup"
done
nvidia-smi --query-gpu=clocks.sm --format=csv | tee -a "$work/gpu.txt"
rc=0
t_start=$(date +%s)
for config in "$@"; do
  name=$(basename "$config" .json)
  t0=$(date +%s)
  left=$(( ${DEADLINE_S:-540} - ($(date +%s) - t_start) ))
  (( left > 10 )) || { echo "$name: not started (deadline)" | tee -a "$work/gpu.txt"; rc=1; continue; }
  timeout -s INT "$left" "$build/lodbench" run "$config" --out "$work/$name" -q || rc=$?
  echo "$name: exit $rc in $(( $(date +%s) - t0 )) s" | tee -a "$work/gpu.txt"
  nvidia-smi --query-gpu=clocks.sm --format=csv,noheader | tee -a "$work/gpu.txt"
done
# Ray-cast truth images and PNGs stay behind: at 1080p they exceed what the device machine returns.
tar -czf "$out/results.tar.gz" --exclude="*/truth" --exclude="*/images" -C "$work" .
exit $rc
