#include "render/terrain_fit.h"

#include "error.h"
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

}  // namespace

void checkTerrainFits(const DeviceLimits& device, const TerrainSpec& spec, const std::string& label) {
  const TerrainShape shape = terrainShape(spec);
  const std::string problem = terrainLimitProblem(device, shape.width, shape.height);
  if (problem.empty()) return;
  throw InputError("terrain '" + label + "'" + (spec.file.empty() ? "" : " (" + spec.file + ")") + ": " + problem +
                   "; the largest square terrain this device takes is " + std::to_string(largestSquareTerrain(device)) +
                   "^2. Way out: " + wayOut(spec, largestSquareTerrain(device)));
}

}  // namespace lb
