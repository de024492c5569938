// Terrain type "gdal" (gdal_loader.h): GDAL's C API, so the C++ ABI of libgdal does not matter.
#include "terrain/gdal_loader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "error.h"
#include "number_text.h"

#if LODBENCH_HAVE_GDAL
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "terrain/parallel_rows.h"
#include "terrain/void_fill.h"
#endif

namespace lb {

#if !LODBENCH_HAVE_GDAL

bool haveGdal() {
  return false;
}

static InputError noGdal(const TerrainSpec& spec) {
  return InputError(spec.file +
                    ": terrain type 'gdal': this build has no GDAL (configured with -DLODBENCH_GDAL=OFF, "
                    "the default with LODBENCH_STATIC_RUNTIME): build with GDAL, or convert the DEM to r32f");
}
Heightfield loadGdal(const TerrainSpec& spec) {
  throw noGdal(spec);
}
std::pair<int, int> gdalTerrainSize(const TerrainSpec& spec) {
  throw noGdal(spec);
}

#else

namespace {

constexpr double kPi = 3.14159265358979323846;
// GDAL's block cache defaults to 5% of the machine's memory; rows are read once, front to back,
// so a small cache loses nothing and keeps a 16385^2 read near the size of the heights alone.
// GDAL_CACHEMAX (environment or config option) still wins.
constexpr int64_t kCacheBytes = 64ll << 20;

void initGdal() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    if (!CPLGetConfigOption("GDAL_CACHEMAX", nullptr)) GDALSetCacheMax64(kCacheBytes);
  });
}

// GDAL prints its errors and warnings to stderr unless a handler is pushed (per thread): keep
// them instead, so they end up in the InputError and nothing else reaches the terminal.
class GdalErrors {
 public:
  GdalErrors() {
    CPLErrorReset();
    CPLPushErrorHandlerEx(&GdalErrors::keep, this);
  }
  ~GdalErrors() { CPLPopErrorHandler(); }
  GdalErrors(const GdalErrors&) = delete;
  GdalErrors& operator=(const GdalErrors&) = delete;
  // Failures if any, else warnings, else "no message".
  std::string text() const {
    return printable(!failures_.empty() ? failures_ : !warnings_.empty() ? warnings_ : "GDAL gave no message", 300);
  }

 private:
  static void CPL_STDCALL keep(CPLErr level, CPLErrorNum, const char* msg) {
    auto* self = static_cast<GdalErrors*>(CPLGetErrorHandlerUserData());
    std::string& out = level >= CE_Failure ? self->failures_ : self->warnings_;
    if (out.size() < 1000) out += (out.empty() ? "" : "; ") + std::string(msg ? msg : "");
  }
  std::string failures_, warnings_;
};

struct CloseDataset {
  void operator()(void* ds) const { GDALClose(ds); }
};
using Dataset = std::unique_ptr<void, CloseDataset>;

Dataset openRaster(const TerrainSpec& spec, const GdalErrors& errors) {
  if (spec.file.empty()) throw InputError("terrain: type 'gdal' needs a file");
  std::error_code ec;
  if (std::filesystem::is_directory(spec.file, ec))
    throw InputError(spec.file + ": is a directory, not a heightmap file");
  if (!std::ifstream(spec.file)) throw InputError("cannot open " + spec.file);
  GDALDatasetH ds = GDALOpenEx(spec.file.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR, nullptr,
                               nullptr, nullptr);
  if (!ds) throw InputError(spec.file + ": GDAL cannot read it as a raster (" + errors.text() + ")");
  return Dataset(ds);
}

std::string str(int64_t v) {
  return std::to_string(v);
}
std::string sizeText(int64_t w, int64_t h) {
  return str(w) + "x" + str(h);
}

// What to read: a region of one band (the chosen band, or its overview) into outW x outH samples.
struct ReadPlan {
  GDALRasterBandH band = nullptr;
  int x = 0, y = 0, w = 0, h = 0;  // region of `band`
  int outW = 0, outH = 0;
  bool average = false;  // outW x outH is smaller than the region: GDAL averages
  // The region in full-resolution pixels (an overview's region maps back to more pixels).
  double fullX = 0, fullY = 0, fullW = 0, fullH = 0;
  TerrainSource source;
};

bool isHeightType(GDALDataType t) {
  return t == GDT_Int16 || t == GDT_UInt16 || t == GDT_Int32 || t == GDT_Float32 || t == GDT_Float64;
}

// Everything from the header: refuses a bad band, type, window or size before anything is allocated.
ReadPlan planRead(GDALDatasetH ds, const TerrainSpec& spec) {
  const std::string& f = spec.file;
  ReadPlan p;
  const int bands = GDALGetRasterCount(ds);
  if (bands < 1) throw InputError(f + ": has no raster band");
  const int bandNo = spec.band > 0 ? spec.band : 1;
  if (bandNo > bands)
    throw InputError(f + ": band " + str(bandNo) + " does not exist (the file has " + str(bands) + ")");
  GDALRasterBandH base = GDALGetRasterBand(ds, bandNo);
  const GDALDataType type = GDALGetRasterDataType(base);
  // The type first: an RGB photo is better told it holds no heights than asked to pick a band.
  if (!isHeightType(type))
    throw InputError(f + ": data type " + GDALGetDataTypeName(type) +
                     " is not a DEM height type (Int16, UInt16, Int32, Float32 or Float64)");
  if (spec.band == 0 && bands > 1)
    throw InputError(f + ": has " + str(bands) + " bands: choose one with \"band\" (1.." + str(bands) + ")");
  const int W = GDALGetRasterXSize(ds), H = GDALGetRasterYSize(ds);
  TerrainSource& s = p.source;
  s.driver = GDALGetDriverShortName(GDALGetDatasetDriver(ds));
  s.rasterWidth = W;
  s.rasterHeight = H;
  s.band = bandNo;
  s.dataType = GDALGetDataTypeName(type);
  s.window = spec.window;
  s.overview = spec.overview;

  int64_t x = 0, y = 0, w = W, h = H;
  if (!spec.window.empty()) {
    if (spec.window.size() != 4) throw InputError(f + ": window must be [x, y, width, height]");
    x = spec.window[0], y = spec.window[1], w = spec.window[2], h = spec.window[3];
    if (x < 0 || y < 0 || w < 2 || h < 2 || x + w > W || y + h > H)
      throw InputError(f + ": window [" + str(x) + ", " + str(y) + ", " + str(w) + ", " + str(h) +
                       "] does not lie within the raster's " + sizeText(W, H) + " pixels (with width, height >= 2)");
  }
  p.band = base;
  p.x = int(x), p.y = int(y), p.w = int(w), p.h = int(h);
  p.outW = p.w, p.outH = p.h;
  p.fullX = double(x), p.fullY = double(y), p.fullW = double(w), p.fullH = double(h);
  const int k = spec.overview;
  if (k > 0) {
    const int count = GDALGetOverviewCount(base);
    if (count > 0) {
      if (k > count)
        throw InputError(f + ": overview " + str(k) + " does not exist: the file has " + str(count) +
                         " overview level(s) (1.." + str(count) + ")");
      GDALRasterBandH ov = GDALGetOverview(base, k - 1);
      const int ow = GDALGetRasterBandXSize(ov), oh = GDALGetRasterBandYSize(ov);
      const double sx = double(ow) / W, sy = double(oh) / H;
      // The window's full-resolution pixels, widened to whole overview pixels.
      const int x0 = int(std::floor(double(x) * sx)), y0 = int(std::floor(double(y) * sy));
      const int x1 = std::min(ow, int(std::ceil(double(x + w) * sx))),
                y1 = std::min(oh, int(std::ceil(double(y + h) * sy)));
      p.band = ov;
      p.x = x0, p.y = y0, p.w = p.outW = x1 - x0, p.h = p.outH = y1 - y0;
      p.fullX = x0 / sx, p.fullY = y0 / sy, p.fullW = (x1 - x0) / sx, p.fullH = (y1 - y0) / sy;
      s.overviewMethod = "file";
    } else {
      // No overviews in the file: the same reduction GDAL's own overviews make (2^k, rounded up).
      const int64_t factor = int64_t(1) << std::min(k, 40);
      p.outW = int((w + factor - 1) / factor), p.outH = int((h + factor - 1) / factor);
      p.average = true;
      s.overviewMethod = "average";
    }
  }
  std::string what = spec.window.empty() ? "the raster" : "the window";
  if (k > 0) what += " at overview " + str(k) + (p.average ? " (2^" + str(k) + " averaging)" : "");
  if (p.outW < 2 || p.outH < 2)
    throw InputError(f + ": " + what + " gives " + sizeText(p.outW, p.outH) + " samples; a terrain needs at least 2x2");
  // Before any allocation: a forged header must not make us ask for gigabytes.
  const int maxSide = spec.page > 0 ? kMaxPagedGdalSide : kMaxGdalSide;
  if (p.outW > maxSide || p.outH > maxSide)
    throw InputError(f + ": " + what + " gives " + sizeText(p.outW, p.outH) + " samples, more than " + str(maxSide) +
                     " per side: use 'overview' or 'window' to read less" +
                     (spec.page > 0 ? std::string() : ", or give the terrain a 'page'"));
  return p;
}

// Metres per degree of longitude on the WGS84 ellipsoid at latitude `latDeg` (the radius of the
// parallel, N(phi) cos(phi), times pi / 180).
double metresPerDegreeLongitude(double latDeg) {
  const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
  const double phi = latDeg * kPi / 180.0, s = std::sin(phi);
  return kPi / 180.0 * a * std::cos(phi) / std::sqrt(1.0 - e2 * s * s);
}

// Fills source's CRS fields and returns the extent: the config's, else (samples - 1) x the sample
// spacing along x in metres, because the renderer puts the first and last samples on the borders.
float resolveExtent(GDALDatasetH ds, const TerrainSpec& spec, const ReadPlan& p, TerrainSource& s) {
  double gt[6];
  const bool hasGt = GDALGetGeoTransform(ds, gt) == CE_None;
  if (hasGt) s.geoTransform.assign(gt, gt + 6);
  OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
  if (srs) {
    const char* name = OSRGetName(srs);
    s.crs = name ? name : "";
    const char* auth = OSRGetAuthorityName(srs, nullptr);
    const char* code = OSRGetAuthorityCode(srs, nullptr);
    if (auth && code && std::string(auth) == "EPSG") s.epsg = std::atoi(code);
  }
  if (spec.extent > 0) {
    s.extentSource = "config";
    return spec.extent;
  }
  auto ask = [&](const std::string& why) -> float {
    throw InputError(spec.file + ": " + why + ": give the terrain an \"extent\" (world units along x)");
  };
  if (!hasGt || !srs) return ask("no CRS and geotransform to derive the extent from");
  if (gt[2] != 0.0 || gt[4] != 0.0) return ask("the geotransform is rotated or sheared");
  const double spacing = std::fabs(gt[1]) * p.fullW / p.outW;  // CRS units between samples along x
  double metres = 0;
  if (OSRIsProjected(srs)) {
    metres = spacing * OSRGetLinearUnits(srs, nullptr);
    s.extentSource = "projected";
  } else if (OSRIsGeographic(srs)) {
    const double degPerUnit = OSRGetAngularUnits(srs, nullptr) * 180.0 / kPi;
    const double lat = (gt[3] + gt[5] * (p.fullY + p.fullH / 2)) * degPerUnit;
    if (!(std::fabs(lat) <= 90.0)) return ask("the centre latitude " + numberText(lat) + " is not within +-90");
    metres = spacing * degPerUnit * metresPerDegreeLongitude(lat);
    s.extentSource = "geographic";
  } else {
    return ask("the CRS '" + printable(s.crs, 80) + "' is neither projected nor geographic");
  }
  const double extent = double(p.outW - 1) * metres;
  if (!(extent >= 1e-3 && extent <= 1e9))
    return ask("the extent from the georeferencing, " + numberText(extent) + " m, is outside [1e-3, 1e9]");
  return float(extent);
}

// A full-resolution read in row bands on every thread (parallel_rows.h), each with its own dataset
// (a GDAL dataset is not thread-safe): the tiles of a mosaic (a VRT) or of a tiled COG are read at
// once, with the same values as one call. Resampled reads (overviews) stay one call.
void readBands(const TerrainSpec& spec, const ReadPlan& p, float* out) {
  const int bandNo = GDALGetBandNumber(p.band);
  std::mutex mutex;
  std::string failure;
  parallelRows(
      p.outH,
      [&](int r0, int r1) {
        GdalErrors errors;
        try {
          Dataset own = openRaster(spec, errors);
          GDALRasterBandH band = GDALGetRasterBand(own.get(), bandNo);
          if (band && GDALRasterIO(band, GF_Read, p.x, p.y + r0, p.w, r1 - r0, out + size_t(r0) * size_t(p.outW),
                                   p.outW, r1 - r0, GDT_Float32, 0, 0) == CE_None)
            return;
          std::lock_guard<std::mutex> lock(mutex);
          failure = spec.file + ": read error (" + errors.text() + ")";
        } catch (const InputError& e) {
          std::lock_guard<std::mutex> lock(mutex);
          failure = e.what();
        }
      },
      256);
  if (!failure.empty()) throw InputError(failure);
}

}  // namespace

bool haveGdal() {
  return true;
}

std::pair<int, int> gdalTerrainSize(const TerrainSpec& spec) {
  initGdal();
  GdalErrors errors;
  Dataset ds = openRaster(spec, errors);
  const ReadPlan p = planRead(ds.get(), spec);
  return {p.outW, p.outH};
}

Heightfield loadGdal(const TerrainSpec& spec) {
  if (!(std::isfinite(spec.extent) && spec.extent >= 0.0f))
    throw InputError(spec.file + ": terrain extent " + std::to_string(spec.extent) +
                     " must be finite and >= 0 (0: from the file)");
  if (!(std::isfinite(spec.heightScale) && spec.heightScale >= 0.0f))
    throw InputError(spec.file + ": terrain heightScale " + std::to_string(spec.heightScale) +
                     " must be finite and >= 0");
  initGdal();
  GdalErrors errors;
  Dataset ds = openRaster(spec, errors);
  ReadPlan p = planRead(ds.get(), spec);
  Heightfield hf;
  hf.width = p.outW;
  hf.height = p.outH;
  hf.extent = resolveExtent(ds.get(), spec, p, p.source);
  // Straight into the heights as float: no second copy of the raster. Row 0 (north in a
  // north-up raster) becomes z = 0, as in the .hgt loader.
  hf.h.resize(size_t(p.outW) * size_t(p.outH));
  GDALRasterIOExtraArg arg;
  INIT_RASTERIO_EXTRA_ARG(arg);
  if (p.average) arg.eResampleAlg = GRIORA_Average;
  if (spec.overview == 0 && !p.average) {
    readBands(spec, p, hf.h.data());
  } else if (GDALRasterIOEx(p.band, GF_Read, p.x, p.y, p.w, p.h, hf.h.data(), p.outW, p.outH, GDT_Float32, 0, 0,
                            &arg) != CE_None) {
    throw InputError(spec.file + ": read error (" + errors.text() + ")");
  }

  // Nodata as GDAL converted it to float (a Float64 nodata may not survive the cast unchanged).
  int hasNodata = 0;
  const double nodata = GDALGetRasterNoDataValue(p.band, &hasNodata);
  float nodataF = 0.0f;
  GDALCopyWords(&nodata, GDT_Float64, 0, &nodataF, GDT_Float32, 0, 1);
  std::vector<char> known;  // allocated at the first void: most DEMs have none
  int64_t voids = 0;
  for (size_t i = 0; i < hf.h.size(); ++i) {
    const float v = hf.h[i];
    if (std::isnan(v) || (hasNodata && v == nodataF)) {
      if (known.empty()) known.assign(hf.h.size(), 1);
      known[i] = 0;
      ++voids;
    } else {
      hf.h[i] = v * spec.heightScale;
    }
  }
  if (voids == int64_t(hf.h.size()))
    throw InputError(spec.file + ": every sample is nodata" +
                     (hasNodata ? " (" + numberText(nodata) + ")" : std::string(" (NaN)")));
  if (voids > 0) fillVoids(hf.h, known, hf.width, hf.height);
  p.source.nodataCount = voids;
  p.source.extent = hf.extent;
  hf.source = std::move(p.source);
  return hf;
}

#endif

}  // namespace lb
