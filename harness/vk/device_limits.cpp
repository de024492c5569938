#include "vk/device_limits.h"

#include <algorithm>
#include <cmath>

namespace lb {
namespace {

constexpr uint64_t kImageBytesPerSample = 4;  // heights R32F; the normal map's R16G16F is as large
constexpr uint64_t kResidentBytesPerSample = 2 * kImageBytesPerSample;

std::string mib(uint64_t bytes) {
  return std::to_string((bytes + (1u << 19)) >> 20) + " MiB";
}

// The bytes a terrain of `samples` needs on each heap at its peak (the second upload, when both
// images and one staging buffer exist).
uint64_t deviceNeed(const DeviceLimits& d, uint64_t samples) {
  return samples * (kResidentBytesPerSample + (d.sharedHeap ? kImageBytesPerSample : 0)) + kDeviceReserveBytes;
}

}  // namespace

DeviceLimits deviceLimits(VkPhysicalDevice pd) {
  DeviceLimits d;
  VkPhysicalDeviceMaintenance3Properties m3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &m3};
  vkGetPhysicalDeviceProperties2(pd, &p2);
  d.name = p2.properties.deviceName;
  d.maxImageDimension2D = p2.properties.limits.maxImageDimension2D;
  d.maxImageArrayLayers = p2.properties.limits.maxImageArrayLayers;
  d.maxAllocationBytes = m3.maxMemoryAllocationSize;
  VkPhysicalDeviceMemoryProperties mem;
  vkGetPhysicalDeviceMemoryProperties(pd, &mem);
  int deviceHeap = -1, stagingHeap = -1;
  for (uint32_t h = 0; h < mem.memoryHeapCount; ++h)
    if ((mem.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) &&
        (deviceHeap < 0 || mem.memoryHeaps[h].size > mem.memoryHeaps[deviceHeap].size))
      deviceHeap = int(h);
  const VkMemoryPropertyFlags staging = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  for (uint32_t t = 0; t < mem.memoryTypeCount && stagingHeap < 0; ++t)
    if ((mem.memoryTypes[t].propertyFlags & staging) == staging) stagingHeap = int(mem.memoryTypes[t].heapIndex);
  if (deviceHeap < 0) deviceHeap = stagingHeap;  // no device-local heap at all: everything is host memory
  if (deviceHeap >= 0) d.deviceHeapBytes = mem.memoryHeaps[deviceHeap].size;
  if (stagingHeap >= 0) d.stagingHeapBytes = mem.memoryHeaps[stagingHeap].size;
  d.sharedHeap = deviceHeap == stagingHeap;
  return d;
}

std::string terrainLimitProblem(const DeviceLimits& d, int width, int height) {
  const std::string size = std::to_string(width) + " x " + std::to_string(height) + " samples";
  if (uint32_t(std::max(width, height)) > d.maxImageDimension2D)
    return size + " exceed " + d.name + "'s maxImageDimension2D of " + std::to_string(d.maxImageDimension2D) +
           " (the terrain is one image of its samples)";
  const uint64_t samples = uint64_t(width) * uint64_t(height);
  if (samples * kImageBytesPerSample > d.maxAllocationBytes)
    return size + " need a " + mib(samples * kImageBytesPerSample) + " height image, more than " + d.name +
           "'s largest allocation (maxMemoryAllocationSize " + mib(d.maxAllocationBytes) + ")";
  if (deviceNeed(d, samples) > d.deviceHeapBytes)
    return size + " need " + mib(deviceNeed(d, samples)) + " of " + d.name + "'s " + mib(d.deviceHeapBytes) +
           " memory heap (" + std::to_string(kResidentBytesPerSample + (d.sharedHeap ? kImageBytesPerSample : 0)) +
           " bytes a sample: heights, normal map" + (d.sharedHeap ? ", staging" : "") + "; plus " +
           mib(kDeviceReserveBytes) + " for render targets and buffers)";
  if (!d.sharedHeap && samples * kImageBytesPerSample > d.stagingHeapBytes)
    return size + " need a " + mib(samples * kImageBytesPerSample) + " staging buffer, more than " + d.name + "'s " +
           mib(d.stagingHeapBytes) + " host-visible heap";
  return "";
}

int largestSquareTerrain(const DeviceLimits& d) {
  // The largest side passing every check; each check is monotonic in the side.
  int lo = 1, hi = int(std::min<uint32_t>(d.maxImageDimension2D, 1u << 20));
  if (!terrainLimitProblem(d, hi, hi).empty()) {
    while (hi - lo > 1) {
      const int mid = lo + (hi - lo) / 2;
      (terrainLimitProblem(d, mid, mid).empty() ? lo : hi) = mid;
    }
    return terrainLimitProblem(d, lo, lo).empty() ? lo : 0;
  }
  return hi;
}

}  // namespace lb
