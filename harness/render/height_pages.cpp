#include "render/height_pages.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "error.h"
#include "render/page_arrays.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"
#include "vk/context.h"
#include "vk/device_limits.h"

namespace lb {
namespace {

// copyPage with the planted defects.
void fillPage(const Heightfield& hf, const PageLayout& l, int i, int j, PageDefect defect, float* out) {
  copyPage(hf, l, i, j, out);
  const int sx = l.storedX(), sz = l.storedZ();
  if (defect == PageDefect::OriginOffByOne && i > 0)
    for (int z = 0; z < sz; ++z)
      for (int x = 0; x < sx; ++x) out[size_t(z) * sx + x] = hf.at(i * l.cellsX + x + 1, j * l.cellsZ + z);
  if (defect == PageDefect::BorderLeftOut && sx > 1)
    for (int z = 0; z < sz; ++z) out[size_t(z) * sx + sx - 1] = out[size_t(z) * sx + sx - 2];
}

}  // namespace

HeightPages createHeightPages(Context& ctx, const Heightfield& hf, MemoryTag tag, PageDefect defect,
                              uint32_t maxLayers) {
  HeightPages out;
  const PageLayout l = pageLayout(hf);
  out.layout = l;
  const uint64_t pageBytes = uint64_t(l.pageSamples()) * sizeof(float);
  const DeviceLimits limits = deviceLimits(ctx.physicalDevice);
  uint32_t perArray = pageLayersPerArray(ctx.props.limits.maxImageArrayLayers, limits.maxAllocationBytes, pageBytes);
  if (maxLayers > 0) perArray = std::min(perArray, maxLayers);
  const int pages = l.pageCount();
  const int arrays = int((uint32_t(pages) + perArray - 1) / perArray);
  if (arrays > LB_HEIGHT_ARRAYS)
    throw FeatureMissing("terrain of " + std::to_string(hf.width) + " x " + std::to_string(hf.height) + " samples in " +
                         std::to_string(pages) + " pages needs " + std::to_string(arrays) + " page arrays of " +
                         std::to_string(perArray) + " layers; the shaders bind " + std::to_string(LB_HEIGHT_ARRAYS) +
                         " (choose a larger 'page')");

  std::vector<uint32_t> table(sizeof(HeightTableHeader) / 4 + size_t(pages));
  HeightTableHeader header{{hf.width, hf.height, l.cellsX, l.cellsZ}, {l.pagesX, l.pagesZ, 0, 0}};
  std::memcpy(table.data(), &header, sizeof header);
  for (int p = 0; p < pages; ++p)
    table[sizeof(HeightTableHeader) / 4 + size_t(p)] =
        uint32_t(p) % perArray | (uint32_t(p) / perArray << LB_PAGE_ARRAY_SHIFT);  // level 0, resident
  out.arrays = uploadPageArrays(
      ctx, uint32_t(l.storedX()), uint32_t(l.storedZ()), VK_FORMAT_R32_SFLOAT, sizeof(float), pages, perArray, tag,
      [&](int p, void* dst) { fillPage(hf, l, p % l.pagesX, p / l.pagesX, defect, static_cast<float*>(dst)); });
  if (defect == PageDefect::WrongLayer && pages > 1)
    table[sizeof(HeightTableHeader) / 4 + size_t(pages / 2)] = table[sizeof(HeightTableHeader) / 4];
  out.table = createBufferWithData(ctx, table.data(), VkDeviceSize(table.size()) * sizeof(uint32_t),
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, tag);
  return out;
}

void writeHeightDescriptors(Context& ctx, VkDescriptorSet set, const HeightPages& pages, VkSampler sampler) {
  writePageDescriptors(ctx, set, LB_BINDING_HEIGHT, LB_HEIGHT_ARRAYS, pages.arrays, LB_BINDING_HEIGHT_TABLE,
                       pages.table, sampler);
}

std::vector<DescriptorBinding> heightBindings(VkShaderStageFlags stages) {
  return {{LB_BINDING_HEIGHT, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, stages, LB_HEIGHT_ARRAYS},
          {LB_BINDING_HEIGHT_TABLE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, stages}};
}

}  // namespace lb
