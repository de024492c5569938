#!/usr/bin/env bash
# The draw paths' real-GPU figures on a machine with an NVIDIA GPU, from a carried static build
# (-DLODBENCH_STATIC_RUNTIME=ON; scripts/device-publish.sh says how the results are packed).
# Usage: scripts/device-draw-paths.sh BUILD_DIR OUT_DIR limit|sweeps CONFIG...
#   limit: CPU selection microbenchmarks (BM_Cdlod*, BM_Clipmap*) on this machine's CPU, then the
#          minimal loops of both draw paths against lodbench's renderer (configs/gpu-limit-paths.json,
#          levels 1-64): OUT_DIR/limit-paths.json, bench-select.json.
#   sweeps: scripts/device-publish.sh with the CONFIGs (OUT_DIR/results.tar.gz).
set -euo pipefail
build=$1 out=$2 part=$3
shift 3
export LODBENCH_SHADER_DIR=$build/shaders
[[ -f $build/COMMIT ]] && export LODBENCH_GIT_COMMIT=$(cat "$build/COMMIT")
mkdir -p "$out"
if [[ $part == limit ]]; then
  # Google Benchmark is a shared library on Debian: carried in BUILD_DIR/lib when the machine lacks it.
  LD_LIBRARY_PATH=$build/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH} "$build/lodbench_bench" \
    --benchmark_filter='BM_Cdlod|BM_Clipmap' --benchmark_repetitions=3 --benchmark_out="$out/bench-select.json" \
    --benchmark_out_format=json | tail -12 || echo "lodbench_bench failed: no CPU selection figures"
  nvidia-smi --query-gpu=name,driver_version,clocks.sm --format=csv | tee "$out/limit-gpu.txt"
  limit=$out/limit-paths.json
  rm -f "$limit"
  # Rows alternate paths level by level, so clock drift hits both alike; each row warms up first.
  for level in 1 2 4 8 16 32 64; do
    frames=100
    ((level == 64)) && frames=40
    for p in tessellation instanced; do
      "$build/lodbench" probe configs/gpu-limit-paths.json --compare --draw-path $p --levels $level --modes shaded \
        --frames $frames --warmup 30 --out "$limit" --append >/dev/null
    done
  done
  nvidia-smi --query-gpu=clocks.sm --format=csv,noheader | tee -a "$out/limit-gpu.txt"
  python3 - "$limit" <<'PY' || true
import json, sys
for r in json.load(open(sys.argv[1]))["rows"]:
    print(f'{r["draw_path"]:13s} level {r["level"]:2d}: minimal {r["minimal_ms"]:.3f} ms, lodbench {r["lodbench_ms"]:.3f} ms, ratio {r["ratio"]:.3f}, triangles {r["triangles"]}, equal {r["counters_equal"]}')
PY
else
  bash scripts/device-publish.sh "$build" "$out" "$@"
fi
