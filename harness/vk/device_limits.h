#pragma once
// What terrain a device can take, stated before any case runs. A terrain lives on the device as
// two images of its full sample grid (heights R32F, normal map R16G16F: 4 + 4 bytes a sample,
// render/renderer_setup.cpp), each filled through a host-visible staging buffer of up to 4 bytes a
// sample. So a terrain needs both sides <= maxImageDimension2D, each image <= the largest single
// allocation, and the bytes above on the heaps they come from (one heap on lavapipe and other
// unified-memory devices: 12 bytes a sample there).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

namespace lb {

struct DeviceLimits {
  std::string name;
  uint32_t maxImageDimension2D = 0;
  uint32_t maxImageArrayLayers = 0;  // layers of one 2D array image (a tiled terrain's pages)
  uint64_t maxAllocationBytes = 0;   // VkPhysicalDeviceMaintenance3Properties::maxMemoryAllocationSize
  uint64_t deviceHeapBytes = 0;      // the largest device-local heap
  uint64_t stagingHeapBytes = 0;     // the heap of host-visible coherent memory (staging buffers)
  bool sharedHeap = false;           // staging and images come from one heap
};

// Bytes kept back on the device heap for everything that is not the terrain: render targets,
// per-patch buffers, scheme textures, the driver's own.
constexpr uint64_t kDeviceReserveBytes = 256ull << 20;

DeviceLimits deviceLimits(VkPhysicalDevice pd);
// "" when a width x height terrain fits; otherwise what it exceeds, with the figures.
std::string terrainLimitProblem(const DeviceLimits& d, int width, int height);
// The largest square terrain (samples per side) the device takes.
int largestSquareTerrain(const DeviceLimits& d);

}  // namespace lb
