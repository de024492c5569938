#pragma once
// Refuses a terrain the device cannot take, before any case runs (a sweep would otherwise fail
// every case of it after loading it, or the driver would fail an allocation mid-run).
#include <string>

#include "terrain/heightfield.h"
#include "vk/device_limits.h"

namespace lb {

// The limit of a terrain whose heights are pages of `page` cells (docs/tiled-heightfield.md): the
// pages' bytes and the normal map's pages (render/normal_pages.h) on the device heap, each in at most
// 8 arrays, not one image. page 0: terrainLimitProblem's single image. "" when it fits.
std::string tiledLimitProblem(const DeviceLimits& d, int width, int height, int page);
// The largest square terrain in pages of `page` cells the device takes.
int largestSquareTiledTerrain(const DeviceLimits& d, int page);

// Throws lb::InputError naming the terrain (label), its size, the limit and the way out; a terrain
// with a "page" is checked against the tiled limit.
void checkTerrainFits(const DeviceLimits& device, const TerrainSpec& spec, const std::string& label);

}  // namespace lb
