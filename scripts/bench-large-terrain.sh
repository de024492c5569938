#!/usr/bin/env bash
# Load benchmark of a large terrain (default 16385^2): load, normal map and every scheme's
# preprocessing (errbound, planefit, density, phong), each stage's wall and CPU seconds and peak
# resident memory, with `lodbench load-bench` (harness/cli/load_bench.h).
#
# The terrain is the procedural one with "detail": "resolution" (fBm octaves down to 2 sample
# spacings, so the extra samples carry relief; the default 8 octaves stop at 1/192 of the extent).
# It is written once to .data/large/ (ignored by git, never committed) as raw float32, then:
#   --source gdal (default): converted to a Float32 GeoTIFF with gdal_translate and loaded as
#                            terrain type gdal (needs GDAL: a build with LODBENCH_GDAL=ON);
#   --source r32f:           loaded as the raw float32 file (any build: the GPU machine's static one);
#   --source procedural:     generated in-process (load = generation), nothing written to disk.
#
# Usage: scripts/bench-large-terrain.sh [--lodbench BIN] [--out DIR] [--source gdal|r32f|procedural]
#                                       [--size N] [--threads N]
# Writes DIR/load-bench-<source>.json and, where GNU time is installed, DIR/time-<source>.txt.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
lodbench=$root/build-large/lodbench
out=$root/results/load-bench
source=gdal
size=16385
threads=0
while (($#)); do
  case $1 in
    --lodbench) lodbench=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --source) source=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    *) echo "usage: $0 [--lodbench BIN] [--out DIR] [--source gdal|r32f|procedural] [--size N] [--threads N]" >&2; exit 2 ;;
  esac
done
case $source in gdal | r32f | procedural) ;; *) echo "$0: --source is gdal, r32f or procedural" >&2; exit 2 ;; esac
data=$root/.data/large
mkdir -p "$data" "$out"
threadArgs=()
((threads > 0)) && threadArgs=(--threads "$threads")
# One km per 1024 samples keeps the DEM-like sample spacing (~1 m) at every size.
extent=$(((size - 1) / 1024 * 1000))
((extent > 0)) || extent=1000
schemes='[{"name": "errbound"}, {"name": "planefit"}, {"name": "density"}, {"name": "phong"}]'
config() {  # config TERRAIN_JSON FILE [SCHEMES_JSON]
  printf '{"name": "load-bench", "grid": 64, "terrain": %s,\n "paths": ["%s/configs/paths/flyover.csv"],\n "schemes": %s}\n' \
    "$1" "$root" "${3:-$schemes}" >"$2"
}
stem=proc${size}-detail
procedural="{\"type\": \"procedural\", \"size\": $size, \"seed\": 1, \"detail\": \"resolution\", \"extent\": $extent, \"height_scale\": 1500}"
config "$procedural" "$data/$stem-procedural.json"
if [[ $source != procedural && ! -s $data/$stem.f32 ]]; then
  # The generator's heights as raw little-endian float32 (what --write-r32f writes); uniform has
  # no preprocessing, so this run only generates.
  config "$procedural" "$data/$stem-write.json" '[{"name": "uniform"}]'
  "$lodbench" load-bench "$data/$stem-write.json" --write-r32f "$data/$stem.f32" "${threadArgs[@]}" >/dev/null
fi
case $source in
  procedural) cfg=$data/$stem-procedural.json ;;
  r32f)
    cfg=$data/$stem-r32f.json
    config "{\"type\": \"r32f\", \"file\": \"$stem.f32\", \"width\": $size, \"height\": $size, \"extent\": $extent}" "$cfg" ;;
  gdal)
    if [[ ! -s $data/$stem.tif ]]; then
      # An ENVI header describes the raw file to GDAL; the GeoTIFF is plain (uncompressed, strips).
      printf 'ENVI\nsamples = %d\nlines = %d\nbands = 1\nheader offset = 0\nfile type = ENVI Standard\ndata type = 4\ninterleave = bsq\nbyte order = 0\n' \
        "$size" "$size" >"$data/$stem.hdr"
      gdal_translate -q -of GTiff -ot Float32 -co BIGTIFF=IF_SAFER "$data/$stem.f32" "$data/$stem.tif"
    fi
    cfg=$data/$stem-gdal.json
    config "{\"type\": \"gdal\", \"file\": \"$stem.tif\", \"extent\": $extent}" "$cfg" ;;
esac
# GNU time's view of the whole process where it is installed (the GPU machines have none; the
# JSON carries each stage's peak from /proc either way).
timer=()
[[ -x /usr/bin/time ]] && timer=(/usr/bin/time -v -o "$out/time-$source.txt")
"${timer[@]}" "$lodbench" load-bench "$cfg" --out "$out/load-bench-$source.json" "${threadArgs[@]}" >/dev/null
[[ -s $out/time-$source.txt ]] && grep -E "Maximum resident|Elapsed" "$out/time-$source.txt" >&2
echo "$out/load-bench-$source.json"
