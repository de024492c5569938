#pragma once
// A terrain's sample grid, known before its samples are read or generated: the device's limits
// (vk/device_limits.h) are checked against it before any case runs.
#include "terrain/heightfield.h"

namespace lb {

struct TerrainShape {
  int width = 0, height = 0;
};

// From the spec, the file's size or its header only. Throws lb::InputError where the loader
// would (a missing file, a size that is no terrain).
TerrainShape terrainShape(const TerrainSpec& spec);

}  // namespace lb
