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
# Usage: scripts/device-suite.sh BUILD_DIR ROOT [CONFIG] [--and ROOT2 [CONFIG2]]... [--gpus N|LIST]
#                               [--deadline S] [--first REGEX] [--keep-claims]
#        scripts/device-suite.sh BUILD_DIR ROOT merge
#   CONFIG      default configs/suite/gpu-h100.json; written once to ROOT/config.json by
#               scripts/run-suite.sh --dry-run (the SRTM tile in place of the crop where found; for
#               the suite's own gpu.json and gpu-h100.json the largest terrain sized to the device;
#               needs python3) unless ROOT/config.json exists
#   --and       one more run in the same queue: its shards are taken after ROOT's, by the same
#               workers, so one call keeps every GPU busy across several configs
#   --gpus      workers: a count N (Vulkan devices 0..N-1, default nvidia-smi's count) or a list of
#               device indices with commas, such as 1,2,3 or 3, (another command has the others)
#   --deadline  seconds from now after which no shard starts and a running one is stopped (default 540);
#               a stopped shard gets 30 s more to write what it keeps, so a caller with a hard time
#               limit sets the deadline at least 40 s inside it
#   --first     workloads whose terrain label matches REGEX are taken first (within each run)
#   --keep-claims  leave the shard claims in place (another invocation on other GPUs shares these
#               runs now); by default an earlier call's claims of unfinished shards are cleared
set -euo pipefail
cd "$(dirname "$0")/.."
build=$1 root=$2
shift 2
config=configs/suite/gpu-h100.json gpus="" deadline=540 first=""
if [[ ${1:-} == merge ]]; then
  [[ -f $build/COMMIT ]] && export LODBENCH_GIT_COMMIT=$(cat "$build/COMMIT")
  mapfile -t done < <(ls -d "$root"/shard-* 2>/dev/null | while read -r d; do [[ -f $d.done ]] && echo "$d"; done)
  echo "merging ${#done[@]} finished shards"
  "$build/lodbench" merge --out "$root/merged" "${done[@]}"
  LODBENCH_SHADER_DIR=$build/shaders "$build/lodbench" verdict "$root/merged"
  "$build/lodbench" report "$root/merged" --no-html
  exit 0
fi
[[ $# -gt 0 && $1 != -* ]] && { config=$1; shift; }
roots=("$root") configs=("$config") keepClaims=0
while [[ $# -gt 0 ]]; do
  case $1 in
    --and)
      roots+=("$2"); shift 2
      if [[ $# -gt 0 && $1 != -* ]]; then configs+=("$1"); shift; else configs+=(configs/suite/gpu-h100.json); fi ;;
    --gpus) gpus=$2; shift 2 ;;
    --deadline) deadline=$2; shift 2 ;;
    --first) first=$2; shift 2 ;;
    --keep-claims) keepClaims=1; shift ;;
    *) echo "device-suite: unknown argument $1" >&2; exit 2 ;;
  esac
done
export LODBENCH_SHADER_DIR=$build/shaders LODBENCH=$build/lodbench
# The carried tree has no up-to-date .git: every result records the build's commit from its COMMIT file.
[[ -f $build/COMMIT ]] && export LODBENCH_GIT_COMMIT=$(cat "$build/COMMIT")
end=$(( $(date +%s) + deadline ))
[[ -n $gpus ]] || gpus=$(nvidia-smi -L | wc -l)
if [[ $gpus == *,* || ! $gpus =~ ^[0-9]+$ ]]; then IFS=, read -ra devices <<<"$gpus"
else devices=(); for (( g = 0; g < gpus; ++g )); do devices+=("$g"); done; fi
# The queue: every run's workloads in its config's order (--first's first), as "run-index shard".
# Workload k of W: the case ids' part after the scheme (terrain, path, resolution, match), once each.
jobs=() counts=()
for r in "${!roots[@]}"; do
  rt=${roots[$r]}
  mkdir -p "$rt"
  # The suite's largest terrain grows to the device's largest (run-suite.sh --largest auto); any
  # other config keeps the terrains it names.
  largest=off
  [[ $(basename "${configs[$r]}") =~ ^gpu(-h100)?\.json$ ]] && largest=auto
  [[ -f $rt/config.json ]] ||
    scripts/run-suite.sh --config "${configs[$r]}" --out "$rt" --dry-run --largest "$largest" >"$rt/dry-run.txt"
  nvidia-smi --query-gpu=index,name,uuid,driver_version,power.limit,clocks.sm,clocks.max.sm --format=csv >>"$rt/gpus.txt" || true
  mapfile -t workloads < <("$LODBENCH" run "$rt/config.json" --dry-run 2>/dev/null | grep -v '^lodbench' |
    sed 's/^[^_]*_//' | awk '!seen[$0]++')
  counts+=("${#workloads[@]}")
  for k in "${!workloads[@]}"; do [[ -n $first && ${workloads[$k]} =~ $first ]] && jobs+=("$r $k"); done
  for k in "${!workloads[@]}"; do [[ -n $first && ${workloads[$k]} =~ $first ]] || jobs+=("$r $k"); done
  (( keepClaims )) || rm -rf "$rt"/claim-*  # claims of an earlier call's unfinished shards
done
worker() {
  local g=$1 job r k rt W left start rc
  for job in "${jobs[@]}"; do
    read -r r k <<<"$job"
    rt=${roots[$r]} W=${counts[$r]}
    [[ -f $rt/shard-$k.done ]] && continue
    mkdir "$rt/claim-$k" 2>/dev/null || continue
    left=$(( end - $(date +%s) ))
    (( left > 20 )) || return 0
    start=$(date +%s)
    rc=0
    timeout -s INT -k 30 "$left" "$LODBENCH" run "$rt/config.json" --out "$rt/shard-$k" --shard "$k/$W" \
      --device "$g" >>"$rt/shard-$k.log" 2>&1 || rc=$?
    # 0: every case ok; 1: ended with failed cases (kept, the verdict names them); 130: stopped.
    if (( rc == 0 || rc == 1 )) && grep -q '^lodbench: [0-9]* ok (' "$rt/shard-$k.log"; then touch "$rt/shard-$k.done"; fi
    echo "gpu $g: $rt shard $k/$W: rc $rc, $(( $(date +%s) - start )) s$([[ -f $rt/shard-$k.done ]] && echo , done)"
  done
}
for g in "${devices[@]}"; do worker "$g" & done
wait
for r in "${!roots[@]}"; do
  n=$(ls "${roots[$r]}"/shard-*.done 2>/dev/null | wc -l)
  echo "device-suite: ${roots[$r]}: $n of ${counts[$r]} shards done"
done
