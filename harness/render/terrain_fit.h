#pragma once
// Refuses a terrain the device cannot take, before any case runs (a sweep would otherwise fail
// every case of it after loading it, or the driver would fail an allocation mid-run).
#include <string>

#include "terrain/heightfield.h"
#include "vk/device_limits.h"

namespace lb {

// Throws lb::InputError naming the terrain (label), its size, the limit and the way out.
void checkTerrainFits(const DeviceLimits& device, const TerrainSpec& spec, const std::string& label);

}  // namespace lb
