#!/usr/bin/env bash
# Produces the published real-GPU figures on a machine with an NVIDIA GPU, from a build carried
# there (build with -DLODBENCH_STATIC_RUNTIME=ON). Usage: scripts/device-bench.sh BUILD_DIR OUT_DIR
# 1. warms the GPU up (it idles at a low clock), 2. the triangle-size sweep (configs/gpu.json),
# 3. measurement passes off/on interleaved twice (configs/gpu-measure-{off,on}.json).
set -euo pipefail
build=$1 out=$2
export LODBENCH_SHADER_DIR=$build/shaders
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv | tee "$out/gpu.txt"
"$build/lodbench" devices | tee -a "$out/gpu.txt"
start=$(date +%s)
while (( $(date +%s) - start < 8 )); do "$build/lodbench" run configs/gpu-measure-off.json --out "$out/warmup" -q >/dev/null; rm -rf "$out/warmup"; done
nvidia-smi --query-gpu=clocks.sm --format=csv | tee -a "$out/gpu.txt"
"$build/lodbench" run configs/gpu.json --out "$out/gpu" -q
for round in 1 2; do
  "$build/lodbench" run configs/gpu-measure-off.json --out "$out/measure-off-$round" -q
  "$build/lodbench" run configs/gpu-measure-on.json --out "$out/measure-on-$round" -q
done
