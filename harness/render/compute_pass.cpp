// Compute preprocessing: own descriptor set and pipeline, created, used once and destroyed, so the
// graphics pipeline layout stays the same for every scheme.
#include "render/compute_pass.h"

#include <cstring>
#include <iterator>

#include "shaders/shared.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace lb {

void runComputePass(Context& ctx, const std::string& stem, VkSampler sampler, VkImageView height, const Image& output,
                    const ComputePush& push) {
  VkDescriptorSetLayoutBinding b[] = {
      {LB_BINDING_HEIGHT, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {LB_BINDING_SCHEME_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
  };
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = uint32_t(std::size(b));
  li.pBindings = b;
  VkDescriptorSetLayout setLayout;
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &li, nullptr, &setLayout));
  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1},
                                  {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.maxSets = 1;
  pi.poolSizeCount = uint32_t(std::size(sizes));
  pi.pPoolSizes = sizes;
  VkDescriptorPool pool;
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &pi, nullptr, &pool));
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &setLayout;
  VkDescriptorSet set;
  VK_CHECK(vkAllocateDescriptorSets(ctx.device, &ai, &set));
  VkDescriptorImageInfo hi{sampler, height, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorImageInfo oi{VK_NULL_HANDLE, output.view, VK_IMAGE_LAYOUT_GENERAL};
  VkWriteDescriptorSet w[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
  w[0].dstSet = w[1].dstSet = set;
  w[0].descriptorCount = w[1].descriptorCount = 1;
  w[0].dstBinding = LB_BINDING_HEIGHT;
  w[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w[0].pImageInfo = &hi;
  w[1].dstBinding = LB_BINDING_SCHEME_IMAGE;
  w[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  w[1].pImageInfo = &oi;
  vkUpdateDescriptorSets(ctx.device, 2, w, 0, nullptr);

  VkPushConstantRange pc{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(ComputePush)};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &setLayout;
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &pc;
  VkPipelineLayout layout;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &pli, nullptr, &layout));
  VkShaderModule module = loadShaderModule(ctx, stem + ".comp.spv");
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = module;
  ci.stage.pName = "main";
  ci.layout = layout;
  VkPipeline pipeline;
  VkResult r = vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline);
  vkDestroyShaderModule(ctx.device, module, nullptr);
  VK_CHECK(r);

  runOneShot(ctx, [&](VkCommandBuffer cmd) {
    imageBarrier(cmd, output.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                 VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                 VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, output.width, output.height, 1);
    // Every graphics stage may sample the result (the tessellation-control shader in practice).
    imageBarrier(cmd, output.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                 VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT,
                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  });
  vkDestroyPipeline(ctx.device, pipeline, nullptr);
  vkDestroyPipelineLayout(ctx.device, layout, nullptr);
  vkDestroyDescriptorPool(ctx.device, pool, nullptr);
  vkDestroyDescriptorSetLayout(ctx.device, setLayout, nullptr);
}

std::vector<float> readImageRgba32f(Context& ctx, const Image& image, int channels) {
  const VkDeviceSize bytes = VkDeviceSize(image.width) * image.height * VkDeviceSize(channels) * sizeof(float);
  Buffer staging;
  createBuffer(ctx, staging, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  runOneShot(ctx, [&](VkCommandBuffer cmd) {
    imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                 VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {image.width, image.height, 1};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &region);
    imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, 0,
                 VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  });
  std::vector<float> out(size_t(bytes / sizeof(float)));
  std::memcpy(out.data(), staging.mapped, size_t(bytes));
  destroyBuffer(ctx, staging);
  return out;
}

}  // namespace lb
