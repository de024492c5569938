// The committed SRTM crop read two ways in a whole sweep: as the .hgt file and as a GeoTIFF written
// here through GDAL's API. Same heights and extent, so every counter and every accuracy metric of
// every frame (histograms, error, image metrics, cracks, popping, surplus) must come out equal;
// only the wall-clock fields may differ.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cli_run.h"
#include "dem_crop.h"
#include "results/run_dir.h"
#include "terrain/gdal_loader.h"

#if LODBENCH_HAVE_GDAL
#include <gdal.h>
#include <ogr_srs_api.h>

namespace {

// The crop as an Int16 GeoTIFF: EPSG:4326, 3 arc-second pixels, first pixel's corner at 71.5 W 44.5 N.
void writeCropTiff(const std::string& out) {
  std::ifstream in(lbtest::demCrop().file, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), 601u * 601u * 2u);
  std::vector<int16_t> samples(601 * 601);
  for (size_t i = 0; i < samples.size(); ++i) samples[i] = int16_t(uint16_t(bytes[2 * i] << 8 | bytes[2 * i + 1]));
  GDALAllRegister();
  GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), out.c_str(), 601, 601, 1, GDT_Int16, nullptr);
  ASSERT_NE(ds, nullptr);
  double gt[6] = {-71.5, 1.0 / 1200, 0, 44.5, 0, -1.0 / 1200};
  GDALSetGeoTransform(ds, gt);
  OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
  OSRImportFromEPSG(srs, 4326);
  GDALSetSpatialRef(ds, srs);
  OSRDestroySpatialReference(srs);
  ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, 601, 601, samples.data(), 601, 601, GDT_Int16, 0, 0),
            CE_None);
  GDALClose(ds);
}

std::string config(const std::string& terrain) {
  return R"({"name": "crop", "resolution": [96, 54], "grid": 8, "fps": 10, "warmup_frames": 0, "max_frames": 6,
  "terrain": )" +
         terrain + R"(, "paths": [")" LODBENCH_SOURCE_DIR R"(/configs/paths/lowalt.csv"],
  "schemes": ["sphere", {"name": "errbound", "params": {"max_error_px": 2}}], "measure": {"every": 3}})";
}

bool isClock(const std::string& key) {
  return key.find("_ms") != std::string::npos || key == "fps" || key == "seconds";
}

}  // namespace

TEST(GdalRun, CropAsGeoTiffGivesTheCountersAndErrorsOfTheCropAsHgt) {
  const std::string dir = lb::test::freshDir("gdal_run");
  std::filesystem::create_directories(dir);
  writeCropTiff(dir + "/crop.tif");
  std::ofstream(dir + "/hgt.json") << config(R"({"type": "hgt", "file": ")" + lbtest::demCrop().file +
                                             R"(", "extent": 54000, "height_scale": 5})");
  std::ofstream(dir + "/gdal.json") << config(
      R"({"type": "gdal", "file": "crop.tif", "extent": 54000, "height_scale": 5})");
  for (const char* name : {"hgt", "gdal"}) {
    lb::test::CliOut o =
        lb::test::lodbench(std::string("run ") + dir + "/" + name + ".json --out " + dir + "/" + name + " -q", false);
    ASSERT_EQ(o.code, 0) << o.text;
  }
  std::vector<nlohmann::json> hgt, gdal;
  for (auto& f : lb::readCaseFiles(dir + "/hgt")) hgt.push_back(f.doc);
  for (auto& f : lb::readCaseFiles(dir + "/gdal")) gdal.push_back(f.doc);
  ASSERT_EQ(hgt.size(), 2u);
  ASSERT_EQ(gdal.size(), hgt.size());
  int measured = 0;
  for (size_t c = 0; c < hgt.size(); ++c) {
    const auto& a = hgt[c]["frames"];
    const auto& b = gdal[c]["frames"];
    SCOPED_TRACE(hgt[c]["scheme"].get<std::string>());
    EXPECT_EQ(hgt[c]["scheme"], gdal[c]["scheme"]);
    EXPECT_EQ(gdal[c]["terrain"]["source"]["driver"], "GTiff");
    ASSERT_EQ(a.size(), b.size());
    for (size_t f = 0; f < a.size(); ++f) {
      ASSERT_EQ(a[f].size(), b[f].size()) << "frame " << f << ": different fields";
      for (auto& [key, value] : a[f].items())
        if (!isClock(key)) EXPECT_EQ(value, b[f][key]) << "frame " << f << " field " << key;
      measured += a[f].contains("err_mean_px") && !a[f]["err_mean_px"].is_null();
    }
  }
  EXPECT_GE(measured, 4) << "too few measured frames to compare errors";  // 2 schemes x frames 0 and 3
}

#else
TEST(GdalRun, CropAsGeoTiffGivesTheCountersAndErrorsOfTheCropAsHgt) {
  GTEST_FAIL() << "this build has no GDAL (LODBENCH_GDAL=OFF): the GeoTIFF path cannot be checked";
}
#endif
