#!/usr/bin/env bash
# The mesh path's workgroup shape measured on a device with VK_EXT_mesh_shader: the same static
# build run with SPIR-V compiled under other defines (LODBENCH_SHADER_DIR), so no rebuild. The
# twins (sphere integer 1, cdlod, cbt) run once, then the mesh schemes once per variant, at equal
# LOD on the SRTM tile's ground, grazing-flight and flyover views (configs under
# results/published/nvidia-h200/mesh/tuning/, which read the SRTM tile from .data/N44W072.hgt: a
# file a clone lacks, put there or named in the configs). scripts/mesh-tuning-table.py tabulates OUT.
# Usage: scripts/mesh-tuning.sh compile OUT          (here: SPIR-V per variant into OUT/v/<name>)
#        scripts/mesh-tuning.sh run OUT BUILD GPU     (on the device: OUT/<variant>/summary.json)
# Variants: name=defines, from LODBENCH_MESH_VARIANTS (default below; shaders/shared.h,
# cdlod_params.h and cbt_meshlets.glsl say what each define sets).
set -euo pipefail
cd "$(dirname "$0")/.."
variants=${LODBENCH_MESH_VARIANTS:-"base= t64=-DLB_MESH_THREADS=64 t128=-DLB_MESH_THREADS=128
  cdlod8x8=-DLB_CDLOD_MS_BLOCK_X=8 cdlod8x4=-DLB_CDLOD_MS_BLOCK_X=8,-DLB_CDLOD_MS_BLOCK_Z=4
  cbt128=-DLB_CBT_MS_OUTPUTS=128 cbt64=-DLB_CBT_MS_OUTPUTS=64"}
cmd=$1 out=$2
conf=results/published/nvidia-h200/mesh/tuning
case $cmd in
  compile)
    for v in $variants; do
      name=${v%%=*} defs=${v#*=}
      mkdir -p "$out/v/$name"
      for f in cbt_ms.mesh cbt_ms.task cdlod_ms.mesh cdlod_ms.task sphere_ms.mesh sphere_ms.task; do
        glslangValidator -V --target-env vulkan1.2 -Ishaders ${defs//,/ } -o "$out/v/$name/$f.spv" "shaders/$f" >/dev/null
      done
    done ;;
  run)
    build=$3 gpu=$4
    one() {  # name config shader-dir
      [[ -f $out/$1/summary.json ]] && return
      LODBENCH_SHADER_DIR=$3 "$build/lodbench" run "$2" --out "$out/$1" -q --device "$gpu" >"$out/$1.log" 2>&1 ||
        echo "mesh-tuning: $1 exited $?"
    }
    one twins $conf/twins.json "$build/shaders"
    for d in "$out"/v/*/; do
      name=$(basename "$d") dir=$(mktemp -d)
      cp "$build"/shaders/*.spv "$dir"/ && cp "$d"/*.spv "$dir"/
      one "$name" $conf/ms.json "$dir"
      echo "mesh-tuning: $name done"
    done ;;
  *) echo "usage: scripts/mesh-tuning.sh compile|run OUT [BUILD GPU]" >&2; exit 2 ;;
esac
