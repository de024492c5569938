// A terrain read from tiles (docs/tiled-heightfield.md): a GDAL VRT mosaic of GeoTIFF tiles, written
// here through GDAL's own API, reads as the same samples as the one raster it was cut from, its
// full-resolution rows read in bands on every thread (terrain/gdal_loader.cpp readBands), and a
// mosaic past one raster's side limit is taken when the terrain has a "page".
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "error.h"
#include "terrain/gdal_loader.h"
#include "terrain/heightfield.h"

#if LODBENCH_HAVE_GDAL
#include <gdal.h>
#include <gdal_utils.h>

namespace fs = std::filesystem;
using namespace lb;

namespace {

constexpr int kW = 700, kH = 1100;  // tiles of 350 x 550; 1100 rows: a band per thread (256 rows or more)

float sampleAt(int x, int y) {
  return float(x % 97) * 1.5f + float(y % 61) * 0.25f + float((x * 7 + y * 13) % 11);
}

// A north-up Float32 GeoTIFF of the samples [x0, x0 + w) x [y0, y0 + h), placed where it lies in
// the whole raster, so the mosaic of the tiles is the whole raster.
void writeTile(const std::string& path, int x0, int y0, int w, int h) {
  GDALAllRegister();
  GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), w, h, 1, GDT_Float32, nullptr);
  ASSERT_NE(ds, nullptr) << path;
  double gt[6] = {double(x0), 1.0, 0.0, -double(y0), 0.0, -1.0};
  GDALSetGeoTransform(ds, gt);
  std::vector<float> v(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) v[size_t(y) * w + x] = sampleAt(x0 + x, y0 + y);
  EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, w, h, v.data(), w, h, GDT_Float32, 0, 0), CE_None);
  GDALClose(ds);
}

TerrainSpec gdalSpec(const std::string& file) {
  TerrainSpec s;
  s.type = "gdal";
  s.file = file;
  s.extent = 1000.0f;
  s.heightScale = 1.0f;
  return s;
}

}  // namespace

TEST(TiledGdal, VrtMosaicOfTilesReadsAsTheWholeRaster) {
  const fs::path dir = fs::path(::testing::TempDir()) / "lodbench_tiled_gdal";
  fs::remove_all(dir);
  fs::create_directories(dir);
  writeTile((dir / "whole.tif").string(), 0, 0, kW, kH);
  std::vector<std::string> tiles;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      tiles.push_back((dir / ("tile" + std::to_string(i) + std::to_string(j) + ".tif")).string());
      writeTile(tiles.back(), i * kW / 2, j * kH / 2, kW / 2, kH / 2);
    }
  std::vector<const char*> names;
  for (const std::string& t : tiles) names.push_back(t.c_str());
  int usageError = 0;
  GDALDatasetH vrt =
      GDALBuildVRT((dir / "mosaic.vrt").c_str(), int(names.size()), nullptr, names.data(), nullptr, &usageError);
  ASSERT_NE(vrt, nullptr);
  GDALClose(vrt);

  const Heightfield whole = makeHeightfield(gdalSpec((dir / "whole.tif").string()));
  TerrainSpec mosaic = gdalSpec((dir / "mosaic.vrt").string());
  mosaic.page = 60;
  const Heightfield tiled = makeHeightfield(mosaic);
  ASSERT_EQ(tiled.width, kW);
  ASSERT_EQ(tiled.height, kH);
  EXPECT_EQ(tiled.page, 60);
  ASSERT_EQ(tiled.h.size(), whole.h.size());
  EXPECT_EQ(std::memcmp(tiled.h.data(), whole.h.data(), whole.h.size() * sizeof(float)), 0);
  size_t wrong = 0;  // and both are the samples written, seam rows and columns included
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) wrong += tiled.h[size_t(y) * kW + x] != sampleAt(x, y);
  EXPECT_EQ(wrong, 0u);
  fs::remove_all(dir);
}

// One raster's side limit is for a single image; a paged terrain goes past it.
TEST(TiledGdal, PagedTerrainsPassOneImagesSideLimit) {
  const fs::path dir = fs::path(::testing::TempDir()) / "lodbench_tiled_gdal_side";
  fs::remove_all(dir);
  fs::create_directories(dir);
  GDALAllRegister();
  // A header only: 20000 x 4 samples of nothing written (GTiff creates it sparse).
  const std::string file = (dir / "long.tif").string();
  GDALDatasetH ds =
      GDALCreate(GDALGetDriverByName("GTiff"), file.c_str(), kMaxGdalSide + 100, 4, 1, GDT_Float32, nullptr);
  ASSERT_NE(ds, nullptr);
  GDALClose(ds);
  TerrainSpec s = gdalSpec(file);
  try {
    gdalTerrainSize(s);
    ADD_FAILURE() << "a single image past the side limit was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("give the terrain a 'page'"), std::string::npos) << e.what();
  }
  s.page = 1023;
  EXPECT_EQ(gdalTerrainSize(s), std::make_pair(kMaxGdalSide + 100, 4));
  fs::remove_all(dir);
}

#endif
