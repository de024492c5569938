#!/usr/bin/env bash
# Writes OUT_DIR/limit.json on a machine with an NVIDIA GPU: lodbench's renderer and the
# minimal tessellation loop (`lodbench probe --compare`) side by side in one session, for uniform
# levels 1, 4, 8, 16, 64 at grid 64 and level 64 at grid 256, at 720p, 1080p and 4K, in every
# timing mode; ratio = minimal_ms / lodbench_ms. About 4 minutes on an H100.
# Usage: scripts/device-limit.sh BUILD_DIR OUT_DIR [--device NAME]   (lavapipe: --device llvmpipe, slow)
set -euo pipefail
build=$1 out=$2
shift 2
export LODBENCH_SHADER_DIR=$build/shaders
# The carried tree's .git may be stale: the commit the build was made from travels as BUILD_DIR/COMMIT.
[[ -f $build/COMMIT ]] && export LODBENCH_GIT_COMMIT=$(cat "$build/COMMIT")
mkdir -p "$out"
limit=$out/limit.json
rm -f "$limit"
if command -v nvidia-smi >/dev/null; then
  nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv | tee "$out/limit-gpu.txt"
fi
t0=$(date +%s)
# The GPU idles at a low clock: each row has its own warm-up frames (--warmup) before its median.
"$build/lodbench" probe configs/gpu-limit.json --compare --levels 1,4,8,16 --frames 100 --warmup 30 --out "$limit" --append "$@" >/dev/null
"$build/lodbench" probe configs/gpu-limit.json --compare --levels 64 --frames 40 --warmup 10 --out "$limit" --append "$@" >/dev/null
# 537 M triangles a frame: ~0.33 s each, so fewer frames.
"$build/lodbench" probe configs/gpu-limit-256.json --compare --levels 64 --frames 8 --warmup 3 --out "$limit" --append "$@" >/dev/null
echo "limit.json: $(grep -c '"mode"' "$limit") rows in $(( $(date +%s) - t0 )) s -> $limit"
if command -v nvidia-smi >/dev/null; then nvidia-smi --query-gpu=clocks.sm --format=csv,noheader | tee -a "$out/limit-gpu.txt"; fi
