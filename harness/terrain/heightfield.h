#pragma once
// A terrain heightfield: samples on a regular grid covering [0, extent] x [0, extent] in world x/z.
// One extent serves both axes (Heightfield::sample, shaders/common.glsl terrainHeight), so sample
// spacing is extent / (width - 1) along x and extent / (height - 1) along z: a non-square grid is
// stretched to a square, as png16 / r16 / r32f files always were.
#include <cstdint>
#include <string>
#include <vector>

#include "uninit_vector.h"

namespace lb {

// What a file terrain was read from, recorded in each case file as "terrain.source"
// (results/write.cpp). driver "" means the terrain was generated, not read.
struct TerrainSource {
  std::string driver;                     // GDAL's driver ("GTiff", "SRTMHGT", ...) or hgt, png16, r16, r32f
  int rasterWidth = 0, rasterHeight = 0;  // the whole file, before window and overview
  int band = 1;
  std::string dataType;              // stored samples: Int16, UInt16, Int32, Float32, Float64
  std::string crs;                   // CRS name, "" = none
  int epsg = 0;                      // 0 = no EPSG code
  std::vector<double> geoTransform;  // the file's, GDAL's 6 coefficients; empty = none
  int64_t nodataCount = 0;           // samples filled as voids (nodata, NaN, SRTM -32768)
  std::vector<int> window;           // [x, y, w, h] read, full-resolution pixels; empty = whole raster
  int overview = 0;                  // level asked for; 0 = full resolution
  std::string overviewMethod;        // "file" (the file's overview) or "average" (2^k averaging); "" = none
  float extent = 0.0f;               // the extent the terrain got
  std::string extentSource;          // config | projected | geographic
};

struct Heightfield {
  int width = 0;           // samples along x
  int height = 0;          // samples along z
  float extent = 1000.0f;  // world size covered along x and z (corner samples sit on the border)
  UninitVector<float> h;   // world-space heights (heightScale applied), row-major, row = z
  float minHeight = 0.0f;
  float maxHeight = 0.0f;
  // World x/z of sample (0, 0): the renderer and camera paths place the terrain there, so a far
  // origin really moves every float position (scenario "far from the origin"). sample() and at()
  // stay terrain-local: subtract the origin first.
  double originX = 0.0, originZ = 0.0;
  TerrainSource source;
  // Cells a device page holds a side (terrain/page_layout.h, docs/tiled-heightfield.md); 0: one page,
  // the single image. The same heights either way: it changes where they live, never a result.
  int page = 0;

  float at(int x, int z) const;  // clamped to the border
  // Bilinear height at world (x, z). Must match shaders/common.glsl terrainHeight() exactly:
  // texel coords t = (p / extent) * (size - 1), clamped, lerp of the 4 neighbours.
  float sample(float worldX, float worldZ) const;
  void updateRange();
  // FNV-1a of the heights' bits (rows in parallel, then over the row hashes): the key of the caches
  // schemes keep of load-time tables (errbound's deviations, cdlod-sse's node errors).
  uint64_t heightHash() const;
};

// Where a heightfield comes from. Mirrors the "terrain" object of a config file.
struct TerrainSpec {
  std::string type = "procedural";      // procedural | hgt | png16 | r16 | r32f | gdal | spikes | cliff | flat | voids
  std::string file;                     // for file types (resolved path)
  int size = 1024;                      // procedural: samples per side
  uint32_t seed = 1;                    // procedural
  int rawWidth = 0, rawHeight = 0;      // r16 / r32f: dimensions (required)
  float extent = 1000.0f;               // world units covered along x and z; gdal: 0 = from the file's georeferencing
  float heightScale = 120.0f;           // procedural: peak height; files: multiplier on stored values
  double originX = 0.0, originZ = 0.0;  // world position of the terrain's (0, 0) corner (Heightfield::originX)
  // procedural (and canyon) "detail": "resolution": fBm octaves continue down to 2 sample spacings, so more
  // samples carry more relief; false ("fixed", the default) keeps the 8 octaves of every earlier run.
  bool detailToSpacing = false;
  int band = 0;             // gdal: raster band, 1-based; 0 = the file's only band
  std::vector<int> window;  // gdal: [x, y, w, h] full-resolution pixels to read; empty = whole raster
  int overview = 0;         // gdal: level k >= 1 (the file's overview k, else 2^k averaging); 0 = full
  int page = 0;             // "page": cells a device page holds a side (Heightfield::page); 0 = one page
};

// Largest |height| accepted, in world units after heightScale. Earth's relief spans -11 km to
// +8.8 km (19.8 km), so 1e5 is 5x that relief in metres (the message and README say so), while
// float32 still resolves 2^-24 * 1e5 ~ 0.006 units there: the error pass, the eye clamp and the
// projections stay meaningful. Beyond it (e.g. r32f values of 1e30) the terrain leaves every
// frustum or overflows squared distances, and the metrics would report a perfect image.
constexpr float kMaxAbsHeight = 1e5f;

// Deterministic ridged + fBm hybrid (Musgrave) in [0,1], scaled by heightScale. Same seed -> same bits.
// Samples are evaluated 8 at a time where the processor has AVX2, else 4 (SSE2). lanes (testing)
// caps that: 1 is the one-at-a-time reference the others must equal bit for bit.
Heightfield makeProcedural(const TerrainSpec& spec, int lanes = 8);
// Loads .hgt (SRTM big-endian int16, N^2 samples: 1201^2 or 3601^2 tiles or crops of them; voids
// -32768 filled), 16-bit PNG, raw R16 / R32F
// and any raster GDAL reads (type gdal, terrain/gdal_loader.h).
// Every type means "stored value x heightScale". Throws lb::InputError naming the file and the
// problem (wrong size, non-finite sample, |height| > kMaxAbsHeight, ...).
Heightfield loadHeightfield(const TerrainSpec& spec);
// The same from the file's bytes (spec.file only names it in messages); the fuzz targets call this.
Heightfield decodeHeightfield(const TerrainSpec& spec, const std::vector<unsigned char>& bytes);
// The .hgt decoder of decodeHeightfield (samples, voids and their fill, height checks) for a grid
// of any side >= 2 without the file-size rule: lets the hgt fuzz target
// (tests/fuzz) explore the decoder with small inputs instead of 2.9 MB tiles.
Heightfield decodeHgtGrid(const TerrainSpec& spec, const std::vector<unsigned char>& bytes, int side);
// Dispatches on spec.type.
Heightfield makeHeightfield(const TerrainSpec& spec);

}  // namespace lb
