#include "render/page_arrays.h"

#include <algorithm>

#include "shaders/shared.h"
#include "vk/context.h"

namespace lb {
namespace {

// Staging of one upload batch: whole layers, at least one.
constexpr uint64_t kStagingBytes = 64ull << 20;

}  // namespace

uint32_t pageLayersPerArray(uint32_t maxImageArrayLayers, uint64_t maxAllocationBytes, uint64_t pageBytes) {
  // Optimal tiling may pad a layer: keep a sixteenth of the largest allocation for it.
  const uint64_t byMemory = (maxAllocationBytes - maxAllocationBytes / 16) / std::max<uint64_t>(pageBytes, 1);
  const uint64_t layers = std::min<uint64_t>({maxImageArrayLayers, LB_PAGE_LAYER_MASK + 1, byMemory});
  return uint32_t(std::max<uint64_t>(layers, 1));
}

void writePageDescriptors(Context& ctx, VkDescriptorSet set, uint32_t arraysBinding, uint32_t slots,
                          const std::vector<Image>& arrays, uint32_t tableBinding, const Buffer& table,
                          VkSampler sampler) {
  std::vector<VkDescriptorImageInfo> images(slots);
  for (size_t a = 0; a < slots; ++a)
    images[a] = {sampler, arrays[a < arrays.size() ? a : 0].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorBufferInfo tableInfo{table.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet w[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
  w[0].dstSet = w[1].dstSet = set;
  w[0].dstBinding = arraysBinding;
  w[0].descriptorCount = slots;
  w[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w[0].pImageInfo = images.data();
  w[1].dstBinding = tableBinding;
  w[1].descriptorCount = 1;
  w[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  w[1].pBufferInfo = &tableInfo;
  vkUpdateDescriptorSets(ctx.device, 2, w, 0, nullptr);
}

std::vector<Image> uploadPageArrays(Context& ctx, uint32_t w, uint32_t h, VkFormat format, uint32_t texelBytes,
                                    int count, uint32_t perArray, MemoryTag tag,
                                    const std::function<void(int page, void* dst)>& fill, VkImageUsageFlags usage) {
  std::vector<Image> arrays;
  const uint64_t pageBytes = uint64_t(w) * h * texelBytes;
  const uint32_t layersPerBatch = uint32_t(std::max<uint64_t>(1, kStagingBytes / pageBytes));
  for (int first = 0; first < count; first += int(perArray)) {
    const int layers = std::min(int(perArray), count - first);
    Image img = createImageArray(ctx, w, h, uint32_t(layers), format,
                                 VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | usage, tag);
    Buffer staging = createBuffer(ctx, VkDeviceSize(std::min<uint64_t>(layers, layersPerBatch) * pageBytes),
                                  VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true, {GpuResource::Staging});
    for (int b = 0; b < layers; b += int(layersPerBatch)) {
      const int n = std::min(int(layersPerBatch), layers - b);
      std::vector<VkBufferImageCopy> regions;
      for (int k = 0; k < n; ++k) {
        fill(first + b + k, static_cast<char*>(staging.mapped) + size_t(k) * pageBytes);
        VkBufferImageCopy region{};
        region.bufferOffset = VkDeviceSize(k) * pageBytes;
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, uint32_t(b + k), 1};
        region.imageExtent = {w, h, 1};
        regions.push_back(region);
      }
      const bool firstBatch = b == 0, lastBatch = b + n >= layers;
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
    arrays.push_back(std::move(img));
  }
  return arrays;
}

}  // namespace lb
