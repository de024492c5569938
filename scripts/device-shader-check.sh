#!/usr/bin/env bash
# The same GPU, the binary before and after the fragment-shader change, interleaved
# (old, new, old, new) over configs/gpu-shader-check.json, plus 1080p renders of flyover frames
# 0 and 80 for an image comparison on the host (scripts/png-diff.py).
# Usage: scripts/device-shader-check.sh OLD_BUILD NEW_BUILD OUT_DIR
set -euo pipefail
old=$1 new=$2 out=$3
mkdir -p "$out"
for round in 1 2; do
  for b in old new; do
    build=${!b}
    LODBENCH_SHADER_DIR=$build/shaders LODBENCH_GIT_COMMIT=$(cat "$build/COMMIT") \
      "$build/lodbench" run configs/gpu-shader-check.json --out "$out/$b-$round" -q
  done
done
for b in old new; do
  build=${!b}
  for f in 0 80; do
    LODBENCH_SHADER_DIR=$build/shaders "$build/lodbench" render --device nvidia --scheme uniform --param level=8 \
      --path configs/paths/flyover.csv --frame "$f" --width 1920 --height 1080 --grid 64 --size 1024 --out "$out/$b-$f.png"
  done
done
rm -rf "$out"/*/cases
