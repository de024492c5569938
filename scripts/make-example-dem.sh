#!/usr/bin/env bash
# Writes the README's "Use your own DEM" example: the committed SRTM crop as a Cloud-Optimized
# GeoTIFF (Int16, EPSG:4326, nodata -32768, DEFLATE, overviews 300^2 and 150^2), the form real
# DEM tiles come in (Copernicus GLO-30, USGS 3DEP). Output: .data/example/N44W072_crop601.tif
# (ignored by git). Needs gdal-bin (installed if missing).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/apt-install.sh" gdal-bin
out=$root/.data/example
mkdir -p "$out"
# An ESRI .hdr beside a copy of the big-endian samples tells GDAL what the crop is: 601 x 601 Int16,
# first sample centred on 71.5 W, 44.5 N, 3 arc-seconds apart (tests/data/README.md).
cp "$root/tests/data/N44W072_crop601.hgt" "$out/crop.bil"
printf '%s\n' "BYTEORDER M" "LAYOUT BIL" "NROWS 601" "NCOLS 601" "NBANDS 1" "NBITS 16" "PIXELTYPE SIGNEDINT" \
  "ULXMAP -71.5" "ULYMAP 44.5" "XDIM 0.000833333333333333" "YDIM 0.000833333333333333" "NODATA -32768" >"$out/crop.hdr"
gdal_translate -q -of COG -a_srs EPSG:4326 -co COMPRESS=DEFLATE -co PREDICTOR=2 -co OVERVIEWS=AUTO \
  -co BLOCKSIZE=256 "$out/crop.bil" "$out/N44W072_crop601.tif"
rm -f "$out/crop.bil" "$out/crop.hdr"
echo "$out/N44W072_crop601.tif"
