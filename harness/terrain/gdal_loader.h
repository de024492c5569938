#pragma once
// Terrain type "gdal": any raster DEM GDAL reads (GeoTIFF, COG, SRTM .hgt, ASCII grid, ...).
// One band of Int16, UInt16, Int32, Float32 or Float64 samples, read straight into the
// heightfield as float x heightScale; nodata (and NaN) samples are filled like SRTM voids. The
// extent comes from the config, else from the georeferencing: (samples - 1) x pixel size along x,
// in metres (projected CRS) or in metres per degree of longitude at the centre latitude
// (geographic CRS, WGS84 ellipsoid), since the samples sit on the extent's borders.
// One extent serves both axes (heightfield.h), so a raster whose rows lie farther apart than its
// columns (any geographic raster away from the equator: a degree of latitude is longer than one
// of longitude) is squeezed along z; reproject it (gdalwarp) for true proportions.
// "window" [x, y, w, h] is in full-resolution pixels. "overview" k reads the file's k-th overview
// (the window widened to whole overview pixels) or, in a file without overviews, averages
// 2^k x 2^k blocks (GDAL's GRIORA_Average, nodata left out; integer samples give integer means).
// Builds without GDAL (LODBENCH_HAVE_GDAL=0, the default of LODBENCH_STATIC_RUNTIME) refuse the
// type with "this build has no GDAL".
#include <utility>

#include "terrain/heightfield.h"

namespace lb {

constexpr int kMaxGdalSide = 16385;  // samples per side after window and overview, as for png16
// The same for a terrain in pages ("page", docs/tiled-heightfield.md): a 1 m DEM of 64 km and more,
// read tile by tile from a mosaic (a VRT) or a tiled COG.
constexpr int kMaxPagedGdalSide = 131073;

// False in builds without GDAL.
bool haveGdal();
// Reads spec.file's band, window and overview; throws InputError naming the file and the problem.
Heightfield loadGdal(const TerrainSpec& spec);
// Width and height in samples that loadGdal would give (after window and overview), from the
// file's header alone: reads no samples. Throws what loadGdal throws for the header (missing band,
// bad data type, window outside the raster, size past kMaxGdalSide, ...).
std::pair<int, int> gdalTerrainSize(const TerrainSpec& spec);

}  // namespace lb
