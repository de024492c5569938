// Terrain type "gdal" (harness/terrain/gdal_loader.h): rasters written here through GDAL's own
// API, read back through the loader, the config parser, the case file and the CLI.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "cli_run.h"
#include "config/config.h"
#include "error.h"
#include "input_error.h"
#include "terrain/gdal_loader.h"
#include "terrain/heightfield.h"

#if LODBENCH_HAVE_GDAL
#include <gdal.h>
#include <ogr_srs_api.h>

#include "dem_crop.h"
#include "results/write.h"
#include "sha256.h"
#include "terrain/generators.h"
#endif

namespace fs = std::filesystem;
using lb::Heightfield;
using lb::InputError;
using lb::TerrainSpec;

namespace {

using lbtest::inputErrorOf;

// A fresh directory per test.
std::string testDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string d = ::testing::TempDir() + "lodbench_gdal/" + info->test_suite_name() + "." + info->name();
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TerrainSpec gdalSpec(const std::string& file, float extent = 0.0f) {
  TerrainSpec s;
  s.type = "gdal";
  s.file = file;
  s.extent = extent;
  s.heightScale = 1.0f;
  return s;
}

}  // namespace

#if !LODBENCH_HAVE_GDAL

TEST(Gdal, BuildWithoutGdalSaysSo) {
  EXPECT_FALSE(lb::haveGdal());
  const std::string msg = inputErrorOf([] { lb::makeHeightfield(gdalSpec("x.tif", 1.0f)); });
  EXPECT_NE(msg.find("this build has no GDAL"), std::string::npos) << msg;
}

#else

namespace {

// A raster to write: band-major samples (band b at b * w * h), row 0 first.
struct Raster {
  int w = 0, h = 0, bands = 1;
  GDALDataType type = GDT_Float32;
  std::vector<double> values;
  int epsg = 0;            // 0: no CRS
  std::vector<double> gt;  // empty: no geotransform
  bool hasNodata = false;
  double nodata = 0;
};

// In memory (driver MEM), for overviews and CreateCopy.
GDALDatasetH memRaster(const Raster& r) {
  GDALAllRegister();
  GDALDatasetH ds = GDALCreate(GDALGetDriverByName("MEM"), "", r.w, r.h, r.bands, r.type, nullptr);
  if (!r.gt.empty()) GDALSetGeoTransform(ds, const_cast<double*>(r.gt.data()));
  if (r.epsg) {
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, r.epsg);
    GDALSetSpatialRef(ds, srs);
    OSRDestroySpatialReference(srs);
  }
  for (int b = 1; b <= r.bands; ++b) {
    GDALRasterBandH band = GDALGetRasterBand(ds, b);
    if (r.hasNodata) GDALSetRasterNoDataValue(band, r.nodata);
    std::vector<double> v(r.values.begin() + size_t(b - 1) * r.w * r.h, r.values.begin() + size_t(b) * r.w * r.h);
    EXPECT_EQ(GDALRasterIO(band, GF_Write, 0, 0, r.w, r.h, v.data(), r.w, r.h, GDT_Float64, 0, 0), CE_None);
  }
  return ds;
}

// A GeoTIFF of r (CreateCopy of the MEM raster, overviews included).
void writeTiff(const std::string& path, GDALDatasetH mem, std::vector<const char*> options = {}) {
  options.push_back(nullptr);
  GDALDatasetH out = GDALCreateCopy(GDALGetDriverByName("GTiff"), path.c_str(), mem, FALSE,
                                    const_cast<char**>(options.data()), nullptr, nullptr);
  ASSERT_NE(out, nullptr) << path;
  GDALClose(out);
}
void writeTiff(const std::string& path, const Raster& r) {
  GDALDatasetH mem = memRaster(r);
  writeTiff(path, mem);
  GDALClose(mem);
}

Raster ramp(int w, int h, GDALDataType type = GDT_Float32) {
  Raster r;
  r.w = w, r.h = h, r.type = type;
  for (int i = 0; i < w * h; ++i) r.values.push_back(double(i % w) + 10.0 * double(i / w));
  return r;
}

std::vector<float> asFloats(const std::vector<double>& v) {
  return std::vector<float>(v.begin(), v.end());
}

double metresPerDegreeLongitude(double latDeg) {  // WGS84: (pi/180) a cos(phi) / sqrt(1 - e2 sin^2 phi)
  const double pi = 3.14159265358979323846, a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2 - f);
  const double phi = latDeg * pi / 180.0;
  return pi / 180.0 * a * std::cos(phi) / std::sqrt(1.0 - e2 * std::sin(phi) * std::sin(phi));
}

}  // namespace

TEST(Gdal, EveryHeightTypeGivesItsExactValues) {
  const std::string dir = testDir();
  struct Case {
    GDALDataType type;
    std::vector<double> values;  // 3 x 2
  };
  const std::vector<Case> cases = {
      {GDT_Int16, {-32767, -1, 0, 1, 8848, 32767}},
      {GDT_UInt16, {0, 1, 2, 1000, 40000, 65535}},
      {GDT_Int32, {-99999, -1, 0, 7, 12345, 99999}},
      {GDT_Float32, {-10994.5, -0.25, 0, 0.125, 1e-3, 8848.86}},
      {GDT_Float64, {-430.5, 1.0 / 3.0, 0, 2.5, 99999.75, 4.0e4}},
  };
  for (const Case& c : cases) {
    const std::string name = GDALGetDataTypeName(c.type);
    SCOPED_TRACE(name);
    Raster r;
    r.w = 3, r.h = 2, r.type = c.type, r.values = c.values;
    const std::string file = dir + "/" + name + ".tif";
    writeTiff(file, r);
    const Heightfield hf = lb::makeHeightfield(gdalSpec(file, 100.0f));
    EXPECT_EQ(hf.width, 3);
    EXPECT_EQ(hf.height, 2);
    EXPECT_EQ(std::vector<float>(hf.h.begin(), hf.h.end()), asFloats(c.values));  // row 0 of the raster is z = 0
    EXPECT_EQ(hf.extent, 100.0f);
    EXPECT_EQ(hf.source.dataType, name);
    EXPECT_EQ(hf.source.driver, "GTiff");
    EXPECT_EQ(hf.source.nodataCount, 0);
    EXPECT_EQ(hf.source.extentSource, "config");
  }
  // height_scale multiplies, as for every file type.
  TerrainSpec s = gdalSpec(dir + "/Int16.tif", 100.0f);
  s.heightScale = 2.0f;
  EXPECT_EQ(lb::makeHeightfield(s).h[4], 2.0f * 8848.0f);
}

TEST(Gdal, NonHeightTypesAreRefused) {
  const std::string dir = testDir();
  Raster rgb = ramp(4, 4, GDT_Byte);
  rgb.bands = 3;
  rgb.values.resize(3 * 16, 7.0);
  writeTiff(dir + "/photo.tif", rgb);
  std::string msg = inputErrorOf([&] { lb::makeHeightfield(gdalSpec(dir + "/photo.tif", 1.0f)); });
  EXPECT_NE(msg.find(dir + "/photo.tif"), std::string::npos) << msg;
  EXPECT_NE(msg.find("data type Byte is not a DEM height type"), std::string::npos) << msg;
  Raster complex = ramp(4, 4, GDT_CFloat32);
  writeTiff(dir + "/complex.tif", complex);
  msg = inputErrorOf([&] { lb::makeHeightfield(gdalSpec(dir + "/complex.tif", 1.0f)); });
  EXPECT_NE(msg.find("data type CFloat32 is not a DEM height type"), std::string::npos) << msg;
}

// Nodata samples are filled exactly as the .hgt loader fills SRTM voids.
TEST(Gdal, NodataIsFilledLikeHgtVoidsAndCounted) {
  const std::string dir = testDir();
  const int n = 9;
  Raster r = ramp(n, n, GDT_Int16);
  r.hasNodata = true, r.nodata = -9999;
  std::vector<unsigned char> hgt;
  int voids = 0;
  for (int i = 0; i < n * n; ++i) {
    const int x = i % n, z = i / n;
    const bool isVoid = (x >= 2 && x <= 5 && z >= 3 && z <= 6) || (x == 8 && z == 0);
    if (isVoid) r.values[size_t(i)] = -9999, ++voids;
    const int16_t m = isVoid ? int16_t(-32768) : int16_t(r.values[size_t(i)]);
    hgt.push_back(uint8_t(uint16_t(m) >> 8)), hgt.push_back(uint8_t(m & 0xff));
  }
  writeTiff(dir + "/voids.tif", r);
  TerrainSpec hs = gdalSpec("voids.hgt", 50.0f);
  hs.type = "hgt";
  const Heightfield want = lb::decodeHgtGrid(hs, hgt, n);
  const Heightfield got = lb::makeHeightfield(gdalSpec(dir + "/voids.tif", 50.0f));
  EXPECT_EQ(got.h, want.h);
  EXPECT_EQ(got.source.nodataCount, voids);
  EXPECT_EQ(want.source.nodataCount, voids);

  // Float rasters: NaN is nodata too, with or without a nodata value.
  Raster f = ramp(4, 3);
  f.values[5] = std::nan("");
  writeTiff(dir + "/nan.tif", f);
  const Heightfield nan = lb::makeHeightfield(gdalSpec(dir + "/nan.tif", 50.0f));
  EXPECT_EQ(nan.source.nodataCount, 1);
  EXPECT_EQ(nan.at(1, 1), (f.values[1] + f.values[4] + f.values[6] + f.values[9]) / 4.0);
}

TEST(Gdal, AllNodataIsAnError) {
  const std::string dir = testDir();
  Raster r = ramp(3, 3, GDT_Int16);
  r.hasNodata = true, r.nodata = 5;
  std::fill(r.values.begin(), r.values.end(), 5.0);
  writeTiff(dir + "/empty.tif", r);
  const std::string msg = inputErrorOf([&] { lb::makeHeightfield(gdalSpec(dir + "/empty.tif", 1.0f)); });
  EXPECT_NE(msg.find(dir + "/empty.tif: every sample is nodata"), std::string::npos) << msg;
}

TEST(Gdal, WindowCropsAndIsCheckedAgainstTheRaster) {
  const std::string dir = testDir();
  writeTiff(dir + "/r.tif", ramp(8, 6));
  TerrainSpec s = gdalSpec(dir + "/r.tif", 10.0f);
  s.window = {2, 1, 4, 3};
  const Heightfield hf = lb::makeHeightfield(s);
  ASSERT_EQ(hf.width, 4);
  ASSERT_EQ(hf.height, 3);
  for (int z = 0; z < 3; ++z)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(hf.at(x, z), float(x + 2) + 10.0f * float(z + 1));
  EXPECT_EQ(hf.source.window, s.window);
  EXPECT_EQ(hf.source.rasterWidth, 8);
  EXPECT_EQ(lb::gdalTerrainSize(s), std::make_pair(4, 3));
  s.window = {5, 0, 4, 3};  // one column past the edge
  const std::string msg = inputErrorOf([&] { lb::makeHeightfield(s); });
  EXPECT_NE(msg.find("window [5, 0, 4, 3] does not lie within the raster's 8x6 pixels"), std::string::npos) << msg;
}

// The samples of a GeoTIFF's first overview, read through GDAL directly.
std::vector<float> firstOverview(const std::string& file) {
  GDALDatasetH ds = GDALOpen(file.c_str(), GA_ReadOnly);
  GDALRasterBandH ov = GDALGetOverview(GDALGetRasterBand(ds, 1), 0);
  const int w = GDALGetRasterBandXSize(ov), h = GDALGetRasterBandYSize(ov);
  std::vector<float> v(size_t(w) * size_t(h));
  EXPECT_EQ(GDALRasterIO(ov, GF_Read, 0, 0, w, h, v.data(), w, h, GDT_Float32, 0, 0), CE_None);
  GDALClose(ds);
  return v;
}

// A file with overviews: overview k is the file's k-th, as stored (here nearest-neighbour, which
// averaging would not give).
TEST(Gdal, OverviewOfTheFileIsUsedWhenPresent) {
  const std::string dir = testDir();
  GDALDatasetH mem = memRaster(ramp(8, 8));
  int levels[] = {2};
  ASSERT_EQ(GDALBuildOverviews(mem, "NEAREST", 1, levels, 0, nullptr, nullptr, nullptr), CE_None);
  writeTiff(dir + "/ov.tif", mem, {"COPY_SRC_OVERVIEWS=YES"});
  GDALClose(mem);
  const std::vector<float> stored = firstOverview(dir + "/ov.tif");
  TerrainSpec s = gdalSpec(dir + "/ov.tif", 10.0f);
  s.overview = 1;
  const Heightfield hf = lb::makeHeightfield(s);
  ASSERT_EQ(hf.width, 4);
  ASSERT_EQ(hf.height, 4);
  EXPECT_EQ(std::vector<float>(hf.h.begin(), hf.h.end()), stored);
  EXPECT_NE(hf.at(0, 0), 5.5f);  // what 2x2 averaging would give
  EXPECT_EQ(hf.source.overviewMethod, "file");
  s.window = {4, 2, 4, 4};  // full-resolution pixels: overview pixels (2, 1) to (3, 2)
  EXPECT_EQ(lb::gdalTerrainSize(s), std::make_pair(2, 2));
  const Heightfield part = lb::makeHeightfield(s);
  EXPECT_EQ(part.at(0, 0), stored[1 * 4 + 2]);
  EXPECT_EQ(part.at(1, 1), stored[2 * 4 + 3]);
  s.window.clear();
  s.overview = 2;
  const std::string msg = inputErrorOf([&] { lb::makeHeightfield(s); });
  EXPECT_NE(msg.find("overview 2 does not exist: the file has 1 overview level(s)"), std::string::npos) << msg;
}

// No overviews in the file: 2^k averaging, rounded up like GDAL's own overview sizes.
TEST(Gdal, OverviewWithoutOverviewsAveragesByTwoToTheK) {
  const std::string dir = testDir();
  writeTiff(dir + "/r.tif", ramp(8, 8));
  TerrainSpec s = gdalSpec(dir + "/r.tif", 10.0f);
  s.overview = 1;
  const Heightfield hf = lb::makeHeightfield(s);
  ASSERT_EQ(hf.width, 4);
  ASSERT_EQ(hf.height, 4);
  for (int z = 0; z < 4; ++z)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(hf.at(x, z), float(2 * x) + 0.5f + 10.0f * (float(2 * z) + 0.5f));
  EXPECT_EQ(hf.source.overviewMethod, "average");
  EXPECT_EQ(hf.source.overview, 1);
  s.overview = 2;
  EXPECT_EQ(lb::gdalTerrainSize(s), std::make_pair(2, 2));
  EXPECT_EQ(lb::makeHeightfield(s).at(0, 0), 1.5f + 15.0f);
  s.overview = 3;  // 1x1
  const std::string msg = inputErrorOf([&] { lb::makeHeightfield(s); });
  EXPECT_NE(msg.find("gives 1x1 samples; a terrain needs at least 2x2"), std::string::npos) << msg;
  writeTiff(dir + "/odd.tif", ramp(9, 5));
  s = gdalSpec(dir + "/odd.tif", 10.0f);
  s.overview = 1;
  EXPECT_EQ(lb::gdalTerrainSize(s), std::make_pair(5, 3));
  // Nodata stays out of the averages. GDAL rounds averages of integer samples to integers, as in
  // the overviews it stores for such files: (1 + 10 + 11) / 3 gives 7.
  Raster r = ramp(4, 4, GDT_Int16);
  r.hasNodata = true, r.nodata = -32768;
  r.values[0] = -32768;
  writeTiff(dir + "/nodata.tif", r);
  s = gdalSpec(dir + "/nodata.tif", 10.0f);
  s.overview = 1;
  EXPECT_EQ(lb::makeHeightfield(s).at(0, 0), 7.0f);
}

TEST(Gdal, ProjectedExtentIsSampleSpacingTimesIntervals) {
  const std::string dir = testDir();
  Raster r = ramp(9, 4);
  r.epsg = 32619;
  r.gt = {300000, 30, 0, 4900000, 0, -30};
  writeTiff(dir + "/utm.tif", r);
  TerrainSpec s = gdalSpec(dir + "/utm.tif");
  Heightfield hf = lb::makeHeightfield(s);
  // The renderer puts the first and last samples on the terrain's borders: 8 intervals of 30 m.
  EXPECT_EQ(hf.extent, 8 * 30.0f);
  EXPECT_EQ(hf.source.extentSource, "projected");
  EXPECT_EQ(hf.source.epsg, 32619);
  EXPECT_NE(hf.source.crs.find("UTM zone 19N"), std::string::npos) << hf.source.crs;
  EXPECT_EQ(hf.source.geoTransform, r.gt);
  s.window = {1, 0, 3, 4};
  EXPECT_EQ(lb::makeHeightfield(s).extent, 2 * 30.0f);
  s.window.clear();
  s.overview = 1;  // 9 -> 5 samples, each 9/5 pixels apart
  EXPECT_FLOAT_EQ(lb::makeHeightfield(s).extent, 4 * 30.0f * 9.0f / 5.0f);
  s = gdalSpec(dir + "/utm.tif", 777.0f);  // the config's extent wins
  hf = lb::makeHeightfield(s);
  EXPECT_EQ(hf.extent, 777.0f);
  EXPECT_EQ(hf.source.extentSource, "config");
}

TEST(Gdal, GeographicExtentUsesMetresPerDegreeAtTheCentreLatitude) {
  const std::string dir = testDir();
  Raster r = ramp(11, 7);
  r.epsg = 4326;
  r.gt = {-71.5, 1.0 / 1200, 0, 44.5, 0, -1.0 / 1200};
  writeTiff(dir + "/geo.tif", r);
  const Heightfield hf = lb::makeHeightfield(gdalSpec(dir + "/geo.tif"));
  const double lat = 44.5 - 3.5 / 1200;
  const double want = 10.0 / 1200 * metresPerDegreeLongitude(lat);
  EXPECT_NEAR(hf.extent / want, 1.0, 1e-6) << hf.extent << " vs " << want;
  EXPECT_EQ(hf.source.extentSource, "geographic");
  EXPECT_EQ(hf.source.epsg, 4326);
  EXPECT_NEAR(metresPerDegreeLongitude(0), 111319.49, 0.01);  // the formula itself: the equator
  EXPECT_EQ(lb::makeHeightfield(gdalSpec(dir + "/geo.tif", 5.0f)).extent, 5.0f);
}

TEST(Gdal, NoGeoreferencingNeedsAConfigExtent) {
  const std::string dir = testDir();
  writeTiff(dir + "/plain.tif", ramp(4, 4));
  const std::string msg = inputErrorOf([&] { lb::makeHeightfield(gdalSpec(dir + "/plain.tif")); });
  EXPECT_NE(msg.find(dir + "/plain.tif: no CRS and geotransform"), std::string::npos) << msg;
  EXPECT_NE(msg.find("\"extent\""), std::string::npos) << msg;
  EXPECT_EQ(lb::makeHeightfield(gdalSpec(dir + "/plain.tif", 3.0f)).extent, 3.0f);
}

TEST(Gdal, MultiBandNeedsABand) {
  const std::string dir = testDir();
  Raster r = ramp(3, 3);
  r.bands = 2;
  for (int i = 0; i < 9; ++i) r.values.push_back(100.0 + i);
  writeTiff(dir + "/two.tif", r);
  TerrainSpec s = gdalSpec(dir + "/two.tif", 1.0f);
  std::string msg = inputErrorOf([&] { lb::makeHeightfield(s); });
  EXPECT_NE(msg.find("has 2 bands: choose one with \"band\""), std::string::npos) << msg;
  s.band = 2;
  const Heightfield hf = lb::makeHeightfield(s);
  EXPECT_EQ(hf.at(0, 0), 100.0f);
  EXPECT_EQ(hf.source.band, 2);
  s.band = 3;
  msg = inputErrorOf([&] { lb::makeHeightfield(s); });
  EXPECT_NE(msg.find("band 3 does not exist (the file has 2)"), std::string::npos) << msg;
}

// A forged (here: sparse) header claiming 40000^2 samples is refused before anything is allocated.
TEST(Gdal, HugeHeaderFailsFast) {
  const std::string dir = testDir(), file = dir + "/huge.tif";
  GDALAllRegister();
  const char* options[] = {"SPARSE_OK=TRUE", "TILED=YES", nullptr};
  GDALDatasetH ds =
      GDALCreate(GDALGetDriverByName("GTiff"), file.c_str(), 40000, 40000, 1, GDT_Int16, const_cast<char**>(options));
  ASSERT_NE(ds, nullptr);
  GDALClose(ds);
  ASSERT_LT(fs::file_size(file), 1u << 20);
  const auto t0 = std::chrono::steady_clock::now();
  const std::string msg = inputErrorOf([&] { lb::makeHeightfield(gdalSpec(file, 1.0f)); });
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2.0);
  EXPECT_NE(msg.find(file + ": the raster gives 40000x40000 samples, more than 16385 per side: use 'overview' or "
                            "'window' to read less"),
            std::string::npos)
      << msg;
  TerrainSpec s = gdalSpec(file, 1.0f);
  s.overview = 2;  // header only: 10000^2 would be read by averaging
  EXPECT_EQ(lb::gdalTerrainSize(s), std::make_pair(10000, 10000));
  s.overview = 0;
  s.window = {100, 200, 64, 32};
  EXPECT_EQ(lb::gdalTerrainSize(s), std::make_pair(64, 32));
  EXPECT_EQ(lb::makeHeightfield(s).width, 64);
}

TEST(Gdal, TruncatedFileFailsNamingItAndPrintsNothing) {
  const std::string dir = testDir(), file = dir + "/cut.tif";
  writeTiff(file, ramp(64, 64));
  fs::resize_file(file, fs::file_size(file) / 2);
  ::testing::internal::CaptureStderr();
  const std::string msg = inputErrorOf([&] { lb::makeHeightfield(gdalSpec(file, 1.0f)); });
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(msg.find(file + ": read error ("), std::string::npos) << msg;
  EXPECT_EQ(printed, "");
  // Not a raster at all.
  std::ofstream(dir + "/text.tif") << "hello";
  ::testing::internal::CaptureStderr();
  const std::string text = inputErrorOf([&] { lb::makeHeightfield(gdalSpec(dir + "/text.tif", 1.0f)); });
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  EXPECT_NE(text.find(dir + "/text.tif: GDAL cannot read it as a raster"), std::string::npos) << text;
}

// An SRTM tile through GDAL's SRTMHGT driver gives the .hgt loader's bits, voids included.
TEST(Gdal, HgtTileThroughGdalIsBitIdentical) {
  const std::string dir = testDir(), file = dir + "/N44W072.hgt";
  lb::writeHgtWithVoid(file, 7, 300, 400, 25);
  TerrainSpec hgt = gdalSpec(file, 54000.0f);
  hgt.type = "hgt";
  const Heightfield a = lb::makeHeightfield(hgt);
  const Heightfield b = lb::makeHeightfield(gdalSpec(file, 54000.0f));
  ASSERT_EQ(a.h.size(), b.h.size());
  EXPECT_EQ(std::memcmp(a.h.data(), b.h.data(), a.h.size() * sizeof(float)), 0);
  EXPECT_EQ(b.source.driver, "SRTMHGT");
  EXPECT_EQ(b.source.nodataCount, 25 * 25);
  EXPECT_EQ(a.source.nodataCount, 25 * 25);
  const Heightfield geo = lb::makeHeightfield(gdalSpec(file));
  EXPECT_EQ(geo.source.extentSource, "geographic");
  EXPECT_EQ(geo.source.epsg, 4326);
  EXPECT_NEAR(geo.extent / metresPerDegreeLongitude(44.5), 1.0, 1e-6);  // one degree at the tile's centre
}

// The committed SRTM crop, converted here to an Int16 GeoTIFF, loads as the .hgt loader reads it.
TEST(Gdal, RealCropAsGeoTiffMatchesHgt) {
  const TerrainSpec hgt = lbtest::demCrop();
  std::ifstream in(hgt.file, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), 601u * 601u * 2u) << hgt.file;
  Raster r;
  r.w = r.h = 601, r.type = GDT_Int16, r.epsg = 4326;
  r.gt = {-71.5, 1.0 / 1200, 0, 44.5, 0, -1.0 / 1200};
  for (size_t i = 0; i < bytes.size(); i += 2)
    r.values.push_back(double(int16_t(uint16_t(bytes[i] << 8 | bytes[i + 1]))));
  const std::string file = testDir() + "/crop.tif";
  writeTiff(file, r);
  TerrainSpec g = gdalSpec(file, hgt.extent);
  g.heightScale = hgt.heightScale;
  // decodeHgtGrid: the .hgt decoder for any side (loadHeightfield's file-size rule aside).
  const Heightfield a = lb::decodeHgtGrid(hgt, bytes, 601), b = lb::makeHeightfield(g);
  EXPECT_EQ(a.h, b.h);
  EXPECT_EQ(a.minHeight, b.minHeight);
  EXPECT_EQ(a.maxHeight, b.maxHeight);
  EXPECT_EQ(b.extent, hgt.extent);
}

// --- The config: fields, labels, case identity and the case file's terrain.source.
namespace {

const std::string kCsv =
    "time,eye_x,eye_y,eye_z,target_x,target_y,target_z,fov\n0,0.1,0.3,0.1,0.5,0,0.5,60\n1,0.9,0.3,0.9,0.5,0,0.5,60\n";

std::string config(const std::string& terrain) {
  return "{\n \"paths\": [\"ok.csv\"],\n \"resolution\": [16, 16], \"grid\": 2, \"warmup_frames\": 0, \"max_frames\": "
         "2,\n"
         " \"schemes\": [{\"name\": \"uniform\", \"params\": {\"level\": 1}}],\n \"terrains\": [\n" +
         terrain + "\n ]\n}\n";
}

lb::Config parse(const std::string& dir, const std::string& terrain) {
  std::ofstream(dir + "/ok.csv") << kCsv;
  return lb::parseConfig(config(terrain), dir + "/c.json", dir);
}

void writeUtm(const std::string& file) {
  Raster r = ramp(9, 5, GDT_Int16);
  r.epsg = 32619;
  r.gt = {300000, 30, 0, 4900000, 0, -30};
  r.hasNodata = true, r.nodata = -32768;
  r.values[3] = -32768;
  writeTiff(file, r);
}

}  // namespace

TEST(GdalConfig, FieldsLabelsAndIdentity) {
  const std::string dir = testDir();
  writeUtm(dir + "/dem.tif");
  lb::Config c = parse(dir,
                       "{\"type\": \"gdal\", \"file\": \"dem.tif\"},\n"
                       "{\"type\": \"gdal\", \"file\": \"dem.tif\", \"window\": [0, 0, 4, 4]},\n"
                       "{\"type\": \"gdal\", \"file\": \"dem.tif\", \"window\": [4, 0, 4, 4]},\n"
                       "{\"type\": \"gdal\", \"file\": \"dem.tif\", \"overview\": 1, \"band\": 1, \"extent\": 50}");
  ASSERT_EQ(c.terrains.size(), 4u);
  EXPECT_EQ(c.terrains[0].extent, 0.0f);  // from the file
  EXPECT_EQ(c.terrains[0].heightScale, 1.0f);
  EXPECT_EQ(c.terrains[3].extent, 50.0f);
  EXPECT_EQ(lb::terrainLabel(c.terrains[0]), "dem");
  EXPECT_EQ(lb::terrainLabel(c.terrains[1]), "dem-w0_0_4x4");
  EXPECT_EQ(lb::terrainLabel(c.terrains[2]), "dem-w4_0_4x4");
  EXPECT_EQ(lb::terrainLabel(c.terrains[3]), "dem-b1-o1");
  const std::vector<lb::Case> cases = lb::expandCases(c);
  ASSERT_EQ(cases.size(), 4u);
  for (size_t i = 0; i < cases.size(); ++i)
    for (size_t j = i + 1; j < cases.size(); ++j) EXPECT_NE(cases[i].terrainDigest, cases[j].terrainDigest);
  EXPECT_EQ(cases[2].inputs["terrain"]["window"], nlohmann::json({4, 0, 4, 4}));
  EXPECT_EQ(cases[3].inputs["terrain"]["overview"], 1);
  EXPECT_EQ(cases[3].inputs["terrain"]["band"], 1);

  // The case file's terrain.source, from the heightfield the runner loaded.
  lb::CaseResult r;
  const lb::Heightfield atOverview = lb::makeHeightfield(cases[3].terrain);
  r.terrainSource = atOverview.source;
  r.terrainWidth = atOverview.width;
  r.terrainHeight = atOverview.height;
  const nlohmann::json t = lb::caseJson(cases[3], r)["terrain"];
  // The grid the overview gave (9 x 5 averaged 2:1, rounded up), not the raster's; a gdal terrain
  // has no size or seed.
  EXPECT_EQ(t["samples"], nlohmann::json({5, 3}));
  EXPECT_FALSE(t.contains("size")) << t.dump();
  EXPECT_FALSE(t.contains("seed")) << t.dump();
  const nlohmann::json& s = t["source"];
  EXPECT_EQ(s["driver"], "GTiff");
  EXPECT_EQ(s["raster_size"], nlohmann::json({9, 5}));
  EXPECT_EQ(s["band"], 1);
  EXPECT_EQ(s["data_type"], "Int16");
  EXPECT_NE(s["crs"].get<std::string>().find("UTM zone 19N"), std::string::npos);
  EXPECT_EQ(s["epsg"], 32619);
  EXPECT_EQ(s["geotransform"], nlohmann::json({300000, 30, 0, 4900000, 0, -30}));
  EXPECT_EQ(s["nodata_count"], 0);  // the averaging left the one nodata sample out
  EXPECT_TRUE(s["window"].is_null());
  EXPECT_EQ(s["overview"], nlohmann::json({{"level", 1}, {"method", "average"}}));
  EXPECT_EQ(s["extent"], 50.0);
  EXPECT_EQ(s["extent_source"], "config");
  EXPECT_EQ(s["sha256"], lb::sha256File(dir + "/dem.tif"));
  r.terrainSource = lb::makeHeightfield(cases[0].terrain).source;
  const nlohmann::json t0 = lb::caseJson(cases[0], r)["terrain"];
  EXPECT_EQ(t0["extent"], 8 * 30.0);
  EXPECT_EQ(t0["source"]["extent_source"], "projected");
  EXPECT_EQ(t0["source"]["nodata_count"], 1);
  EXPECT_TRUE(lb::caseJson(cases[0], lb::CaseResult{})["terrain"]["source"].is_null());  // never read
  // Generated terrains have no source, "voids" (written to a temporary .hgt and read back) included.
  TerrainSpec voids;
  voids.type = "voids";
  voids.heightScale = 1.0f;  // metres, as the config parser sets for this type
  EXPECT_TRUE(lb::makeHeightfield(voids).source.driver.empty());
}

TEST(GdalConfig, FieldsOfOtherTypesAreRefused) {
  const std::string dir = testDir();
  writeUtm(dir + "/dem.tif");
  lb::writeHgtWithVoid(dir + "/N44W072.hgt", 1, 0, 0, 0);
  struct Bad {
    std::string terrain, expect;
  };
  const std::vector<Bad> bad = {
      {"{\"type\": \"hgt\", \"file\": \"N44W072.hgt\", \"window\": [0, 0, 4, 4]}", "does not use 'window' (only gdal"},
      {"{\"type\": \"png16\", \"file\": \"dem.tif\", \"band\": 1}", "does not use 'band'"},
      {"{\"type\": \"procedural\", \"overview\": 1}", "does not use 'overview'"},
      {"{\"type\": \"gdal\", \"file\": \"dem.tif\", \"size\": 64}", "does not use 'size'"},
      {"{\"type\": \"gdal\", \"file\": \"dem.tif\", \"width\": 9, \"height\": 5}", "does not use 'width'"},
      {"{\"type\": \"gdal\", \"file\": \"dem.tif\", \"window\": [0, 0, 4]}", "expected [x, y, width, height]"},
      {"{\"type\": \"gdal\", \"file\": \"dem.tif\", \"window\": [0, 0, 1, 4]}", "/window/2"},
      {"{\"type\": \"gdal\", \"file\": \"dem.tif\", \"overview\": 0}", "/overview"},
      {"{\"type\": \"gdal\", \"file\": \"dem.tif\", \"band\": 0}", "/band"},
      {"{\"type\": \"gdal\", \"file\": \"dem.tif\", \"band\": 2}", "band 2 does not exist"},
      {"{\"type\": \"gdal\"}", "needs a 'file'"},
      {"{\"type\": \"tiff\"}", "procedural, hgt, png16, r16, r32f, gdal, spikes"},
  };
  for (const Bad& b : bad) {
    SCOPED_TRACE(b.terrain);
    const std::string msg = inputErrorOf([&] { parse(dir, b.terrain); });
    EXPECT_NE(msg.find(b.expect), std::string::npos) << msg;
  }
}

// --- The CLI: each bad raster exits 2 naming the config, the file and the reason, and creates nothing.
TEST(GdalCli, BadRastersExitTwoAndWriteNothing) {
  const std::string dir = testDir();
  std::ofstream(dir + "/ok.csv") << kCsv;
  GDALAllRegister();
  const char* sparse[] = {"SPARSE_OK=TRUE", "TILED=YES", nullptr};
  GDALClose(GDALCreate(GDALGetDriverByName("GTiff"), (dir + "/huge.tif").c_str(), 40000, 40000, 1, GDT_Int16,
                       const_cast<char**>(sparse)));
  writeTiff(dir + "/cut.tif", ramp(64, 64));
  fs::resize_file(dir + "/cut.tif", fs::file_size(dir + "/cut.tif") / 2);
  Raster rgb = ramp(4, 4, GDT_Byte);
  rgb.bands = 3;
  rgb.values.resize(48, 1.0);
  writeTiff(dir + "/rgb.tif", rgb);
  Raster empty = ramp(3, 3);
  empty.hasNodata = true, empty.nodata = 0;
  std::fill(empty.values.begin(), empty.values.end(), 0.0);
  writeTiff(dir + "/empty.tif", empty);
  Raster two = ramp(3, 3);
  two.bands = 2;
  two.values.resize(18, 1.0);
  writeTiff(dir + "/two.tif", two);
  writeTiff(dir + "/plain.tif", ramp(4, 4));
  struct Row {
    std::string name, terrain;
    std::vector<std::string> expect;
  };
  const std::vector<Row> rows = {
      {"huge",
       "{\"type\": \"gdal\", \"file\": \"huge.tif\", \"extent\": 1}",
       {"huge.tif: the raster gives 40000x40000 samples", "use 'overview' or 'window'"}},
      {"truncated", "{\"type\": \"gdal\", \"file\": \"cut.tif\", \"extent\": 1}", {"cut.tif: read error"}},
      {"rgb",
       "{\"type\": \"gdal\", \"file\": \"rgb.tif\", \"extent\": 1}",
       {"rgb.tif: data type Byte is not a DEM height type"}},
      {"all_nodata",
       "{\"type\": \"gdal\", \"file\": \"empty.tif\", \"extent\": 1}",
       {"empty.tif: every sample is nodata"}},
      {"multi_band", "{\"type\": \"gdal\", \"file\": \"two.tif\", \"extent\": 1}", {"two.tif: has 2 bands"}},
      {"window_outside",
       "{\"type\": \"gdal\", \"file\": \"plain.tif\", \"extent\": 1, \"window\": [2, 2, 3, 3]}",
       {"plain.tif: window [2, 2, 3, 3] does not lie within"}},
      {"no_georeference",
       "{\"type\": \"gdal\", \"file\": \"plain.tif\"}",
       {"plain.tif: no CRS and geotransform", "\"extent\""}},
  };
  for (const Row& row : rows) {
    SCOPED_TRACE(row.name);
    const std::string cfg = dir + "/" + row.name + ".json";
    std::ofstream(cfg) << config(row.terrain);
    const auto before = std::distance(fs::directory_iterator(dir), fs::directory_iterator());
    const auto t0 = std::chrono::steady_clock::now();
    const lb::test::CliOut o = lb::test::lodbench("run " + cfg + " --out " + dir + "/out-" + row.name + " --quiet");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10.0);
    EXPECT_EQ(o.code, 2) << o.text;
    EXPECT_NE(o.text.find(row.name + ".json:6"), std::string::npos) << o.text;
    EXPECT_NE(o.text.find("'/terrains/0/file'"), std::string::npos) << o.text;
    for (const std::string& e : row.expect) EXPECT_NE(o.text.find(e), std::string::npos) << e << "\n" << o.text;
    EXPECT_FALSE(fs::exists(dir + "/out-" + row.name));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), before);  // no .aux.xml either
  }
}

// A whole run on a GeoTIFF: the case file records where the terrain came from.
TEST(GdalCli, RunRecordsTheSourceInTheCaseFile) {
  const std::string dir = testDir();
  std::ofstream(dir + "/ok.csv") << kCsv;
  writeUtm(dir + "/dem.tif");
  std::ofstream(dir + "/c.json") << config(
      "{\"type\": \"gdal\", \"file\": \"dem.tif\", \"window\": [1, 0, 8, 5]},\n"
      "{\"type\": \"gdal\", \"file\": \"dem.tif\", \"overview\": 1}");
  const lb::test::CliOut o = lb::test::lodbench("run " + dir + "/c.json --out " + dir + "/out --quiet");
  ASSERT_EQ(o.code, 0) << o.text;
  std::map<std::string, nlohmann::json> terrains;  // by label
  for (auto& e : fs::directory_iterator(dir + "/out/cases")) {
    const nlohmann::json t = lb::test::readJson(e.path().string())["terrain"];
    terrains[t["label"].get<std::string>()] = t;
  }
  ASSERT_EQ(terrains.size(), 2u);
  // Read at overview 1: the 5 x 3 samples it loaded, beside the 9 x 5 raster.
  const nlohmann::json& o1 = terrains["dem-o1"];
  EXPECT_EQ(o1["samples"], nlohmann::json({5, 3})) << o1.dump();
  EXPECT_EQ(o1["source"]["raster_size"], nlohmann::json({9, 5}));
  EXPECT_EQ(o1["source"]["overview"]["level"], 1);
  for (auto& [label, terrain] : terrains) {
    EXPECT_FALSE(terrain.contains("size")) << terrain.dump();
    EXPECT_FALSE(terrain.contains("seed")) << terrain.dump();
  }
  const nlohmann::json t = terrains["dem-w1_0_8x5"];
  EXPECT_EQ(t["samples"], nlohmann::json({8, 5}));
  EXPECT_EQ(t["label"], "dem-w1_0_8x5");
  EXPECT_EQ(t["extent"], 7 * 30.0);
  EXPECT_EQ(t["source"]["driver"], "GTiff");
  EXPECT_EQ(t["source"]["window"], nlohmann::json({1, 0, 8, 5}));
  EXPECT_EQ(t["source"]["extent_source"], "projected");
  EXPECT_EQ(t["source"]["nodata_count"], 1);
  EXPECT_EQ(t["source"]["sha256"], lb::sha256File(dir + "/dem.tif"));
}

#endif
