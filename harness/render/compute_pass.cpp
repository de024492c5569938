// Compute preprocessing: own descriptor set and pipeline, created, used once and released, so the
// graphics pipeline layout stays the same for every scheme.
#include "render/compute_pass.h"

#include <cstring>

#include "render/height_pages.h"
#include "render/pipeline.h"
#include "shaders/shared.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace lb {

void runComputePass(Context& ctx, const std::string& stem, VkSampler sampler, const HeightPages& heights,
                    const Image& output, const ComputePush& push) {
  // Owned by locals: released on return and when any step below throws.
  std::vector<DescriptorBinding> layout = heightBindings(VK_SHADER_STAGE_COMPUTE_BIT);
  layout.push_back({LB_BINDING_SCHEME_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT});
  Bindings bindings = createBindings(ctx, layout, VK_SHADER_STAGE_COMPUTE_BIT, sizeof(ComputePush));
  writeHeightDescriptors(ctx, bindings.set, heights, sampler);
  VkDescriptorImageInfo oi{VK_NULL_HANDLE, output.view, VK_IMAGE_LAYOUT_GENERAL};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = bindings.set;
  w.descriptorCount = 1;
  w.dstBinding = LB_BINDING_SCHEME_IMAGE;
  w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  w.pImageInfo = &oi;
  vkUpdateDescriptorSets(ctx.device, 1, &w, 0, nullptr);

  vk::Unique<VkPipeline> pipeline = createComputePipeline(ctx, bindings.pipelineLayout, stem);

  runOneShot(ctx, [&](VkCommandBuffer cmd) {
    imageBarrier(cmd, output.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                 VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                 VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, bindings.pipelineLayout, 0, 1, &bindings.set, 0,
                            nullptr);
    vkCmdPushConstants(cmd, bindings.pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, output.width, output.height, 1);
    // Every graphics stage may sample the result (the tessellation-control shader in practice).
    imageBarrier(cmd, output.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                 VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT,
                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  });
}

std::vector<float> readImageRgba32f(Context& ctx, const Image& image, int channels) {
  const VkDeviceSize bytes =
      VkDeviceSize(image.width) * image.height * image.layers * VkDeviceSize(channels) * sizeof(float);
  Buffer staging = createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, {GpuResource::Staging});
  runOneShot(ctx, [&](VkCommandBuffer cmd) {
    imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                 VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, image.layers};
    region.imageExtent = {image.width, image.height, 1};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &region);
    imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, 0,
                 VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                  VK_ACCESS_2_HOST_READ_BIT);
  });
  std::vector<float> out(size_t(bytes / sizeof(float)));
  std::memcpy(out.data(), staging.mapped, size_t(bytes));
  return out;
}

}  // namespace lb
