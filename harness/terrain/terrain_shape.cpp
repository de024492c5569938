#include "terrain/terrain_shape.h"

#include <stb/stb_image.h>  // declarations only; terrain_loader.cpp holds the implementation

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "error.h"
#include "terrain/gdal_loader.h"
#include "terrain/generators.h"

namespace lb {

TerrainShape terrainShape(const TerrainSpec& spec) {
  if (spec.type == "procedural") return {spec.size, spec.size};
  if (spec.type == "voids") return {1201, 1201};
  if (isGeneratedTerrain(spec.type)) return {spec.size, spec.size};
  if (spec.type == "r16" || spec.type == "r32f") return {spec.rawWidth, spec.rawHeight};
  if (spec.type == "hgt") {
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(spec.file, ec);
    if (ec) throw InputError("cannot open " + spec.file);
    const int n = int(std::llround(std::sqrt(double(bytes / 2))));
    return {n, n};
  }
  if (spec.type == "png16") {
    int w = 0, h = 0, comp = 0;
    if (!stbi_info(spec.file.c_str(), &w, &h, &comp)) throw InputError(spec.file + ": cannot read PNG header");
    return {w, h};
  }
  if (spec.type == "gdal") {
    const auto [w, h] = gdalTerrainSize(spec);
    return {w, h};
  }
  throw InputError(spec.file + ": '" + spec.type + "' is not a terrain type");
}

}  // namespace lb
