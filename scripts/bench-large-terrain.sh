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
#   --source vrt:            cut into K x K Float32 GeoTIFF tiles (--tiles K, default 4) that share
#                            their edge samples, as SRTM tiles do (adjacent tiles overlap by one
#                            sample, so the mosaic has exactly N x N samples), joined by gdalbuildvrt
#                            and loaded as terrain type gdal: a DEM that comes as many tiles (needs GDAL);
#   --source r32f:           loaded as the raw float32 file (any build: the GPU machine's static one);
#   --source procedural:     generated in-process (load = generation), nothing written to disk.
# gdal and vrt use GDAL's command-line tools (gdal-bin, installed if missing).
# Past 16385 samples a side (one GDAL raster's limit, kMaxGdalSide; one image stops at 32768) every
# source's terrain gets "page": 1023: the loaders then take it, and no load-bench stage reads the page.
#
# Usage: scripts/bench-large-terrain.sh [--lodbench BIN] [--out DIR] [--source gdal|vrt|r32f|procedural]
#                                       [--size N] [--tiles K] [--threads N]
# Writes DIR/load-bench-<source>.json and, where GNU time is installed, DIR/time-<source>.txt.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
lodbench=$root/build-large/lodbench
out=$root/results/load-bench
source=gdal
size=16385
threads=0
tiles=4
while (($#)); do
  case $1 in
    --lodbench) lodbench=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --source) source=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --tiles) tiles=$2; shift 2 ;;
    *) echo "usage: $0 [--lodbench BIN] [--out DIR] [--source gdal|vrt|r32f|procedural] [--size N] [--tiles K] [--threads N]" >&2; exit 2 ;;
  esac
done
case $source in gdal | vrt | r32f | procedural) ;; *) echo "$0: --source is gdal, vrt, r32f or procedural" >&2; exit 2 ;; esac
# A tile needs at least 2 samples a side.
if ! [[ $tiles =~ ^[1-9][0-9]*$ ]] || ((tiles > size - 1)); then
  echo "$0: --tiles is 1..$((size - 1))" >&2
  exit 2
fi
[[ $source == gdal || $source == vrt ]] && bash "$root/scripts/apt-install.sh" gdal-bin
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
page=""
((size > 16385)) && page=', "page": 1023'
stem=proc${size}-detail
procedural="{\"type\": \"procedural\", \"size\": $size, \"seed\": 1, \"detail\": \"resolution\", \"extent\": $extent, \"height_scale\": 1500$page}"
config "$procedural" "$data/$stem-procedural.json"
if [[ $source != procedural && ! -s $data/$stem.f32 ]]; then
  # The generator's heights as raw little-endian float32 (what --write-r32f writes); uniform has
  # no preprocessing, so this run only generates.
  config "$procedural" "$data/$stem-write.json" '[{"name": "uniform"}]'
  "$lodbench" load-bench "$data/$stem-write.json" --write-r32f "$data/$stem.f32" "${threadArgs[@]}" >/dev/null
fi
# An ENVI header describes the raw file to GDAL (it opens $stem.f32 through $stem.hdr).
envi() {
  printf 'ENVI\nsamples = %d\nlines = %d\nbands = 1\nheader offset = 0\nfile type = ENVI Standard\ndata type = 4\ninterleave = bsq\nbyte order = 0\n' \
    "$size" "$size" >"$data/$stem.hdr"
}
case $source in
  procedural) cfg=$data/$stem-procedural.json ;;
  r32f)
    cfg=$data/$stem-r32f.json
    config "{\"type\": \"r32f\", \"file\": \"$stem.f32\", \"width\": $size, \"height\": $size, \"extent\": $extent$page}" "$cfg" ;;
  gdal)
    if [[ ! -s $data/$stem.tif ]]; then
      # The GeoTIFF is plain (uncompressed, strips).
      envi
      gdal_translate -q -of GTiff -ot Float32 -co BIGTIFF=IF_SAFER "$data/$stem.f32" "$data/$stem.tif"
    fi
    cfg=$data/$stem-gdal.json
    config "{\"type\": \"gdal\", \"file\": \"$stem.tif\", \"extent\": $extent$page}" "$cfg" ;;
  vrt)
    mosaic=$stem-tiles$tiles
    if [[ ! -s $data/$mosaic.vrt ]]; then
      envi
      rm -rf "${data:?}/$mosaic"
      mkdir -p "$data/$mosaic"
      # Tile edges at sample floor(i (N - 1) / K); tile i holds samples edge(i) .. edge(i + 1), both
      # ends included, so neighbours share that row or column. The raw file has no georeferencing and
      # gdalbuildvrt places tiles by theirs: each tile gets its own pixel bounds (1 unit a sample,
      # north-up), whole numbers, so the mosaic's grid is the raster's and nothing is resampled.
      edge() { echo $(($1 * (size - 1) / tiles)); }
      list=()
      for ((j = 0; j < tiles; ++j)); do
        y0=$(edge $j) y1=$(edge $((j + 1)))
        for ((i = 0; i < tiles; ++i)); do
          x0=$(edge $i) x1=$(edge $((i + 1)))
          tile=$mosaic/r${j}c$i.tif
          gdal_translate -q -of GTiff -ot Float32 -co BIGTIFF=IF_SAFER -srcwin "$x0" "$y0" $((x1 - x0 + 1)) $((y1 - y0 + 1)) \
            -a_ullr "$x0" $((-y0)) $((x1 + 1)) $((-(y1 + 1))) "$data/$stem.f32" "$data/$tile"
          list+=("$data/$tile")
        done
      done
      gdalbuildvrt -q "$data/$mosaic.vrt" "${list[@]}"
    fi
    cfg=$data/$mosaic-vrt.json
    config "{\"type\": \"gdal\", \"file\": \"$mosaic.vrt\", \"extent\": $extent$page}" "$cfg" ;;
esac
# GNU time's view of the whole process where it is installed (the GPU machines have none; the
# JSON carries each stage's peak from /proc either way).
timer=()
[[ -x /usr/bin/time ]] && timer=(/usr/bin/time -v -o "$out/time-$source.txt")
"${timer[@]}" "$lodbench" load-bench "$cfg" --out "$out/load-bench-$source.json" "${threadArgs[@]}" >/dev/null
[[ -s $out/time-$source.txt ]] && grep -E "Maximum resident|Elapsed" "$out/time-$source.txt" >&2
echo "$out/load-bench-$source.json"
