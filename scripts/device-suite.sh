#!/usr/bin/env bash
# The workload suite on a machine with one or more NVIDIA GPUs, from a static build carried there
# (-DLODBENCH_STATIC_RUNTIME=ON). One shard per workload (`run --shard k/W` gives whole workloads,
# so every scheme of a workload is timed on one GPU); one worker per GPU takes the next shard not
# yet taken, so long and short workloads balance. An interleaved shard writes its cases after its
# last round, so a deadline stops workers between shards and stops (SIGINT) a shard that would not
# end in time: it keeps its cases' searches (searches/ in the shard's folder), and the next call
# runs only their timing and measurement again. Call again with the same ROOT to go on (each
# shard's log grows by the calls); "merge" joins the finished shards, writes verdict.json and the
# report.
# Usage: scripts/device-suite.sh BUILD_DIR ROOT [CONFIG] [--gpus N] [--deadline S] [--first REGEX]
#        scripts/device-suite.sh BUILD_DIR ROOT merge
#   CONFIG      default configs/suite/gpu-h100.json; written once to ROOT/config.json by
#               scripts/run-suite.sh --dry-run (the SRTM tile in place of the crop where found,
#               the largest terrain sized to the device; needs python3) unless ROOT/config.json exists
#   --gpus      workers (default: nvidia-smi's count); worker g runs on Vulkan device g
#   --deadline  seconds from now after which no shard starts and a running one is stopped (default 540)
#   --first     workloads whose terrain label matches REGEX are taken first
set -euo pipefail
cd "$(dirname "$0")/.."
build=$1 root=$2
shift 2
config=configs/suite/gpu-h100.json gpus="" deadline=540 first=""
if [[ ${1:-} == merge ]]; then
  mapfile -t done < <(ls -d "$root"/shard-* 2>/dev/null | while read -r d; do [[ -f $d.done ]] && echo "$d"; done)
  echo "merging ${#done[@]} finished shards"
  "$build/lodbench" merge --out "$root/merged" "${done[@]}"
  LODBENCH_SHADER_DIR=$build/shaders "$build/lodbench" verdict "$root/merged"
  "$build/lodbench" report "$root/merged" --no-html
  exit 0
fi
[[ $# -gt 0 && $1 != -* ]] && { config=$1; shift; }
while [[ $# -gt 0 ]]; do
  case $1 in
    --gpus) gpus=$2; shift 2 ;;
    --deadline) deadline=$2; shift 2 ;;
    --first) first=$2; shift 2 ;;
    *) echo "device-suite: unknown argument $1" >&2; exit 2 ;;
  esac
done
export LODBENCH_SHADER_DIR=$build/shaders LODBENCH=$build/lodbench
end=$(( $(date +%s) + deadline ))
[[ -n $gpus ]] || gpus=$(nvidia-smi -L | wc -l)
mkdir -p "$root"
[[ -f $root/config.json ]] || scripts/run-suite.sh --config "$config" --out "$root" --dry-run >"$root/dry-run.txt"
nvidia-smi --query-gpu=index,name,uuid,driver_version,power.limit,clocks.sm,clocks.max.sm --format=csv >>"$root/gpus.txt" || true
# Workload k of W in the config's order: the case ids' part after the scheme (terrain, path,
# resolution, match), once each.
mapfile -t workloads < <("$LODBENCH" run "$root/config.json" --dry-run 2>/dev/null | grep -v '^lodbench' |
  sed 's/^[^_]*_//' | awk '!seen[$0]++')
W=${#workloads[@]}
order=()
for k in "${!workloads[@]}"; do [[ -n $first && ${workloads[$k]} =~ $first ]] && order+=("$k"); done
for k in "${!workloads[@]}"; do [[ -n $first && ${workloads[$k]} =~ $first ]] || order+=("$k"); done
rm -rf "$root"/claim-*  # claims of an earlier call's unfinished shards
worker() {
  local g=$1 k left start rc
  for k in "${order[@]}"; do
    [[ -f $root/shard-$k.done ]] && continue
    mkdir "$root/claim-$k" 2>/dev/null || continue
    left=$(( end - $(date +%s) ))
    (( left > 20 )) || return 0
    start=$(date +%s)
    rc=0
    timeout -s INT -k 30 "$left" "$LODBENCH" run "$root/config.json" --out "$root/shard-$k" --shard "$k/$W" \
      --device "$g" >>"$root/shard-$k.log" 2>&1 || rc=$?
    # 0: every case ok; 1: ended with failed cases (kept, the verdict names them); 130: stopped.
    if (( rc == 0 || rc == 1 )) && grep -q '^lodbench: [0-9]* ok (' "$root/shard-$k.log"; then touch "$root/shard-$k.done"; fi
    echo "gpu $g: shard $k/$W (${workloads[$k]}): rc $rc, $(( $(date +%s) - start )) s$([[ -f $root/shard-$k.done ]] && echo , done)"
  done
}
for (( g = 0; g < gpus; ++g )); do worker "$g" & done
wait
n=$(ls "$root"/shard-*.done 2>/dev/null | wc -l)
echo "device-suite: $n of $W shards done"
