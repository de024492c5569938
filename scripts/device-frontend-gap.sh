#!/usr/bin/env bash
# Attributes the frontend-mode gap at uniform level 1 (limit.json: lodbench 0.023 ms,
# minimal loop 0.022 ms). Three interleaved rounds of `probe --compare --modes frontend` with the
# plain minimal loop and with its --vertex-height variant (control-point height fetch, as lodbench's
# vertex shader), at grid 64 and grid 256 (16x the patches: a per-patch cost grows 16x, a per-frame
# cost does not). Writes OUT_DIR/frontend-gap-<grid>-<variant>-<round>.json.
# Usage: scripts/device-frontend-gap.sh BUILD_DIR OUT_DIR [--device NAME]
set -euo pipefail
build=$1 out=$2
shift 2
export LODBENCH_SHADER_DIR=$build/shaders
[[ -f $build/COMMIT ]] && export LODBENCH_GIT_COMMIT=$(cat "$build/COMMIT")
mkdir -p "$out"
sed -e 's#"grid": 64#"grid": 256#' -e 's#"paths/#"'"$PWD"'/configs/paths/#' configs/gpu-limit.json >"$out/gpu-limit-256-frontend.json"
# Sustained load first: the GPU idles at a low clock.
"$build/lodbench" probe configs/gpu-limit.json --levels 64 --modes shaded --frames 200 --warmup 10 "$@" >/dev/null 2>&1
for round in 1 2 3; do
  for grid in 64 256; do
    cfg=configs/gpu-limit.json
    [[ $grid == 256 ]] && cfg=$out/gpu-limit-256-frontend.json
    for variant in plain vertex-height; do
      flag=()
      [[ $variant == vertex-height ]] && flag=(--vertex-height)
      "$build/lodbench" probe "$cfg" --compare --modes frontend --levels 1,4 --frames 200 --warmup 50 "${flag[@]}" \
        --out "$out/frontend-gap-$grid-$variant-$round.json" "$@" >/dev/null
    done
  done
done
echo "frontend-gap: $(ls "$out"/frontend-gap-*.json | wc -l) files -> $out"
