#include "render/sample_map_pages.h"

#include <algorithm>
#include <cstring>

#include "render/compute_pass.h"
#include "render/page_arrays.h"
#include "render/scheme.h"
#include "shaders/shared.h"
#include "terrain/parallel_rows.h"
#include "vk/context.h"

namespace lb {

std::vector<Image> createSampleMapPages(Context& ctx, const HeightPages& heights, const SampleMap& map, MemoryTag tag) {
  const PageLayout& l = heights.layout;
  const int sx = l.storedX(), sz = l.storedZ();
  // Page p of the heights lies in array p / perArray at layer p % perArray: the same here.
  const uint32_t perArray = heights.arrays.at(0).layers;
  auto fill = [&](int p, void* dst) {
    const int x0 = (p % l.pagesX) * l.cellsX, z0 = (p / l.pagesX) * l.cellsZ;
    const int inside = std::max(0, std::min(sx, l.samplesX - x0));
    float* out = static_cast<float*>(dst);
    // As copyPage: past the terrain's +x or +z edge the edge sample repeats (never read by a shader).
    parallelRows(
        sz,
        [&](int r0, int r1) {
          for (int r = r0; r < r1; ++r) {
            float* row = out + size_t(r) * size_t(sx);
            map.row(std::min(z0 + r, l.samplesZ - 1), x0, inside, row);
            std::fill(row + inside, row + sx, row[inside - 1]);
          }
        },
        16);
  };
  return uploadPageArrays(ctx, uint32_t(sx), uint32_t(sz), VK_FORMAT_R32_SFLOAT, sizeof(float), l.pageCount(), perArray,
                          tag, fill, VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
}

void writeSampleMapDescriptors(Context& ctx, VkDescriptorSet set, const std::vector<Image>& arrays,
                               const HeightPages& heights, VkSampler sampler) {
  const std::vector<Image>& bound = arrays.empty() ? heights.arrays : arrays;
  std::vector<VkDescriptorImageInfo> images(LB_HEIGHT_ARRAYS);
  for (size_t a = 0; a < images.size(); ++a)
    images[a] = {sampler, bound[a < bound.size() ? a : 0].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set;
  w.dstBinding = LB_BINDING_SAMPLE_MAP;
  w.descriptorCount = uint32_t(images.size());
  w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w.pImageInfo = images.data();
  vkUpdateDescriptorSets(ctx.device, 1, &w, 0, nullptr);
}

DescriptorBinding sampleMapBinding(VkShaderStageFlags stages) {
  return {LB_BINDING_SAMPLE_MAP, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, stages, LB_HEIGHT_ARRAYS};
}

std::vector<float> readSampleMapPages(Context& ctx, const HeightPages& heights, const std::vector<Image>& arrays) {
  const PageLayout& l = heights.layout;
  const size_t pageFloats = l.pageSamples();
  std::vector<float> paged;
  for (const Image& a : arrays) {
    const std::vector<float> layers = readImageRgba32f(ctx, a, 1);
    paged.insert(paged.end(), layers.begin(), layers.end());
  }
  std::vector<float> out(size_t(l.samplesX) * size_t(l.samplesZ));
  for (int z = 0; z < l.samplesZ; ++z)
    for (int x = 0; x < l.samplesX; ++x) {
      const int i = l.pageOfX(x), j = l.pageOfZ(z);
      const size_t page = size_t(j) * size_t(l.pagesX) + size_t(i);
      out[size_t(z) * size_t(l.samplesX) + size_t(x)] =
          paged[page * pageFloats + size_t(z - j * l.cellsZ) * size_t(l.storedX()) + size_t(x - i * l.cellsX)];
    }
  return out;
}

}  // namespace lb
