#!/usr/bin/env bash
# The GPU verdict run (configs/gpu-verdict-mini.json, or CONFIG) on a machine with an NVIDIA GPU,
# from a static build carried there (-DLODBENCH_STATIC_RUNTIME=ON). An interleaved sweep writes
# its cases after its last round, so it runs as shards small enough for one device call each;
# then "merge" joins them, writes verdict.json and the report.
# Usage: scripts/device-verdict.sh BUILD_DIR RUN_ROOT i/n [CONFIG]   (one shard, 0-based)
#        scripts/device-verdict.sh BUILD_DIR RUN_ROOT merge
set -euo pipefail
build=$1 root=$2 what=$3 config=${4:-configs/gpu-verdict-mini.json}
export LODBENCH_SHADER_DIR=$build/shaders
mkdir -p "$root"
if [[ $what == merge ]]; then
  "$build/lodbench" merge --out "$root/merged" "$root"/shard-*
  "$build/lodbench" verdict "$root/merged"
  "$build/lodbench" report "$root/merged" --no-html
  exit 0
fi
nvidia-smi --query-gpu=name,uuid,driver_version,power.limit,clocks.sm,clocks.max.sm --format=csv \
  | tee "$root/gpu-shard-${what%/*}.txt"
start=$(date +%s)
"$build/lodbench" run "$config" --out "$root/shard-${what%/*}" --shard "$what" -q
echo "shard $what: $(( $(date +%s) - start )) s" | tee -a "$root/gpu-shard-${what%/*}.txt"
