#pragma once
// Pages as layers of 2D array images: the heights' (render/height_pages.h) and the normal map's
// (render/normal_pages.h). Page p lies in array p / perArray at layer p % perArray.
#include <cstdint>
#include <functional>
#include <vector>

#include "vk/resources.h"

namespace lb {

struct Context;

// `count` pages of w x h texels of `texelBytes` each, uploaded through a bounded staging buffer:
// fill(p, dst) writes page p's texels, row-major. Arrays are left SHADER_READ_ONLY_OPTIMAL.
// `usage` adds to SAMPLED | TRANSFER_DST (TRANSFER_SRC for a map tests read back).
std::vector<Image> uploadPageArrays(Context& ctx, uint32_t w, uint32_t h, VkFormat format, uint32_t texelBytes,
                                    int count, uint32_t perArray, MemoryTag tag,
                                    const std::function<void(int page, void* dst)>& fill, VkImageUsageFlags usage = 0);

// Writes `slots` elements of the arrays' combined-image-sampler binding (those past the arrays repeat
// the first) and the table's storage-buffer binding of `set`.
void writePageDescriptors(Context& ctx, VkDescriptorSet set, uint32_t arraysBinding, uint32_t slots,
                          const std::vector<Image>& arrays, uint32_t tableBinding, const Buffer& table,
                          VkSampler sampler);

// How many page layers one array of this device takes for pages of `pageBytes` bytes.
uint32_t pageLayersPerArray(uint32_t maxImageArrayLayers, uint64_t maxAllocationBytes, uint64_t pageBytes);

}  // namespace lb
