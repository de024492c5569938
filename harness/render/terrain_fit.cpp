#include "render/terrain_fit.h"

#include <algorithm>

#include "error.h"
#include "render/normal_pages.h"
#include "render/page_arrays.h"
#include "shaders/shared.h"
#include "terrain/page_layout.h"
#include "terrain/terrain_shape.h"

namespace lb {
namespace {

std::string wayOut(const TerrainSpec& spec, int largest) {
  const std::string side = std::to_string(largest);
  if (spec.type == "gdal")
    return "read a coarser level with 'overview' (each level halves both sides) or crop it with 'window' (at most " +
           side + " x " + side + " samples)";
  if (spec.type == "procedural" || spec.type == "spikes" || spec.type == "cliff" || spec.type == "flat" ||
      spec.type == "canyon")
    return "choose a 'size' of at most " + side;
  return "load the file as type 'gdal' with 'overview' or 'window', or resample it to at most " + side + " x " + side +
         " samples";
}

std::string mib(uint64_t bytes) {
  return std::to_string((bytes + (1u << 19)) >> 20) + " MiB";
}

}  // namespace

std::string tiledLimitProblem(const DeviceLimits& d, int width, int height, int page) {
  if (page <= 0) return terrainLimitProblem(d, width, height);
  const std::string size = std::to_string(width) + " x " + std::to_string(height) + " samples";
  const PageLayout l = pageLayout(width, height, page);
  if (uint32_t(std::max(l.storedX(), l.storedZ())) > d.maxImageDimension2D)
    return "pages of " + std::to_string(page) + " cells exceed " + d.name + "'s maxImageDimension2D of " +
           std::to_string(d.maxImageDimension2D);
  const uint64_t pageBytes = uint64_t(l.pageSamples()) * sizeof(float);
  const uint32_t perArray = pageLayersPerArray(d.maxImageArrayLayers, d.maxAllocationBytes, pageBytes);
  const uint64_t arrays = (uint64_t(l.pageCount()) + perArray - 1) / perArray;
  if (arrays > LB_HEIGHT_ARRAYS)
    return size + " in " + std::to_string(l.pageCount()) + " pages of " + std::to_string(page) + " cells need " +
           std::to_string(arrays) + " page arrays of " + std::to_string(perArray) + " layers on " + d.name +
           "; the shaders bind " + std::to_string(LB_HEIGHT_ARRAYS);
  // The normal map's pages (render/normal_pages.h), uploaded through a bounded staging buffer.
  const NormalPagesFit normals = normalPagesFit(width, height, d.maxImageArrayLayers, d.maxAllocationBytes);
  if (normals.arrays > LB_NORMAL_ARRAYS)
    return size + " need a normal map of " + std::to_string(normals.arrays) + " page arrays of " +
           std::to_string(normals.perArray) + " layers on " + d.name + "; the shaders bind " +
           std::to_string(LB_NORMAL_ARRAYS);
  const uint64_t pagesBytes = pageBytes * uint64_t(l.pageCount());
  const uint64_t need = pagesBytes + normals.bytes + kDeviceReserveBytes;
  if (need > d.deviceHeapBytes)
    return size + " in pages of " + std::to_string(page) + " cells need " + mib(need) + " of " + d.name + "'s " +
           mib(d.deviceHeapBytes) + " memory heap (height pages " + mib(pagesBytes) + ", normal map pages " +
           mib(normals.bytes) + "; plus " + mib(kDeviceReserveBytes) + " for render targets and buffers)";
  return "";
}

int largestSquareTiledTerrain(const DeviceLimits& d, int page) {
  if (page <= 0) return largestSquareTerrain(d);
  // Each check grows with the side: the largest side passing them all, by bisection.
  int lo = 2, hi = 1 << 20;
  if (!tiledLimitProblem(d, lo, lo, page).empty()) return 0;
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    (tiledLimitProblem(d, mid, mid, page).empty() ? lo : hi) = mid;
  }
  return lo;
}

void checkTerrainFits(const DeviceLimits& device, const TerrainSpec& spec, const std::string& label) {
  const TerrainShape shape = terrainShape(spec);
  const std::string problem = tiledLimitProblem(device, shape.width, shape.height, spec.page);
  if (problem.empty()) return;
  const int largest = largestSquareTiledTerrain(device, spec.page);
  throw InputError("terrain '" + label + "'" + (spec.file.empty() ? "" : " (" + spec.file + ")") + ": " + problem +
                   "; the largest square terrain this device takes" +
                   (spec.page > 0 ? " in pages of " + std::to_string(spec.page) + " cells" : std::string()) + " is " +
                   std::to_string(largest) + "^2. Way out: " + wayOut(spec, largest));
}

}  // namespace lb
