#include "render/height_pages.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "error.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"
#include "vk/context.h"
#include "vk/device_limits.h"

namespace lb {
namespace {

// Staging of one upload batch: whole layers, at least one.
constexpr uint64_t kStagingBytes = 64ull << 20;

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

uint32_t pageLayersPerArray(uint32_t maxImageArrayLayers, uint64_t maxAllocationBytes, uint64_t pageBytes) {
  // Optimal tiling may pad a layer: keep a sixteenth of the largest allocation for it.
  const uint64_t byMemory = (maxAllocationBytes - maxAllocationBytes / 16) / std::max<uint64_t>(pageBytes, 1);
  const uint64_t layers = std::min<uint64_t>({maxImageArrayLayers, LB_PAGE_LAYER_MASK + 1, byMemory});
  return uint32_t(std::max<uint64_t>(layers, 1));
}

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
  const uint32_t layersPerBatch = uint32_t(std::max<uint64_t>(1, kStagingBytes / pageBytes));
  for (int a = 0; a < arrays; ++a) {
    const int first = a * int(perArray), count = std::min(int(perArray), pages - first);
    Image img =
        createImageArray(ctx, uint32_t(l.storedX()), uint32_t(l.storedZ()), uint32_t(count), VK_FORMAT_R32_SFLOAT,
                         VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, tag);
    Buffer staging = createBuffer(ctx, VkDeviceSize(std::min<uint64_t>(count, layersPerBatch) * pageBytes),
                                  VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true, {GpuResource::Staging});
    for (int b = 0; b < count; b += int(layersPerBatch)) {
      const int n = std::min(int(layersPerBatch), count - b);
      std::vector<VkBufferImageCopy> regions;
      for (int k = 0; k < n; ++k) {
        const int p = first + b + k;
        fillPage(hf, l, p % l.pagesX, p / l.pagesX, defect,
                 reinterpret_cast<float*>(static_cast<char*>(staging.mapped) + size_t(k) * pageBytes));
        table[sizeof(HeightTableHeader) / 4 + size_t(p)] =
            uint32_t(b + k) | (uint32_t(a) << LB_PAGE_ARRAY_SHIFT);  // level 0, resident
        VkBufferImageCopy region{};
        region.bufferOffset = VkDeviceSize(k) * pageBytes;
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, uint32_t(b + k), 1};
        region.imageExtent = {uint32_t(l.storedX()), uint32_t(l.storedZ()), 1};
        regions.push_back(region);
      }
      const bool firstBatch = b == 0, lastBatch = b + n >= count;
      runOneShot(ctx, [&](VkCommandBuffer cmd) {
        if (firstBatch)
          imageBarrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COPY_BIT,
                       VK_ACCESS_2_TRANSFER_WRITE_BIT);
        vkCmdCopyBufferToImage(cmd, staging.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(regions.size()), regions.data());
        if (lastBatch)
          imageBarrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                       VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                       VK_ACCESS_2_SHADER_READ_BIT);
      });
    }
    out.arrays.push_back(std::move(img));
  }
  if (defect == PageDefect::WrongLayer && pages > 1)
    table[sizeof(HeightTableHeader) / 4 + size_t(pages / 2)] = table[sizeof(HeightTableHeader) / 4];
  out.table = createBufferWithData(ctx, table.data(), VkDeviceSize(table.size()) * sizeof(uint32_t),
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, tag);
  return out;
}

void writeHeightDescriptors(Context& ctx, VkDescriptorSet set, const HeightPages& pages, VkSampler sampler) {
  VkDescriptorImageInfo images[LB_HEIGHT_ARRAYS];
  for (size_t a = 0; a < LB_HEIGHT_ARRAYS; ++a)
    images[a] = {sampler, pages.arrays[a < pages.arrays.size() ? a : 0].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorBufferInfo table{pages.table.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet w[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
  w[0].dstSet = w[1].dstSet = set;
  w[0].dstBinding = LB_BINDING_HEIGHT;
  w[0].descriptorCount = LB_HEIGHT_ARRAYS;
  w[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w[0].pImageInfo = images;
  w[1].dstBinding = LB_BINDING_HEIGHT_TABLE;
  w[1].descriptorCount = 1;
  w[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  w[1].pBufferInfo = &table;
  vkUpdateDescriptorSets(ctx.device, 2, w, 0, nullptr);
}

std::vector<DescriptorBinding> heightBindings(VkShaderStageFlags stages) {
  return {{LB_BINDING_HEIGHT, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, stages, LB_HEIGHT_ARRAYS},
          {LB_BINDING_HEIGHT_TABLE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, stages}};
}

}  // namespace lb
