#include "metrics/gpu_flip.h"

#include <stdexcept>
#include <string>

#include "metrics/flip_color.h"
#include "render/pipeline.h"
#include "shaders/flip_params.h"
#include "vk/context.h"

namespace lb {

GpuFlip::GpuFlip(Context& ctx, int width, int height, double ppd)
    : ctx_(ctx), width_(width), height_(height), ppd_(ppd), kernels_(flipKernels(ppd)) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("GpuFlip: empty image");
  const VkDeviceSize n = VkDeviceSize(width) * VkDeviceSize(height);
  std::vector<float> k(LB_FLIP_K_KERNELS, 0.0f);
  for (int b = 0; b < 256; ++b) k[LB_FLIP_K_LINEAR + size_t(b)] = float(srgbToLinear(b));
  k[LB_FLIP_K_BY_WEIGHT] = float(kernels_.blueYellowWeight[0]);
  k[LB_FLIP_K_BY_WEIGHT + 1] = float(kernels_.blueYellowWeight[1]);
  k[LB_FLIP_K_CMAX] = float(kernels_.cmax);
  for (const std::vector<double>* v : {&kernels_.achromatic, &kernels_.redGreen, &kernels_.blueYellow[0],
                                       &kernels_.blueYellow[1], &kernels_.gauss, &kernels_.edge, &kernels_.point})
    for (double w : *v) k.push_back(float(w));
  kernelBuffer_ = createBufferWithData(ctx, k.data(), k.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       {GpuResource::Measure});
  planes_ = createBuffer(ctx, n * 2 * LB_FLIP_PLANES * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false,
                         {GpuResource::Measure});
  map_ = createBuffer(ctx, n * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                      false, {GpuResource::Measure});
  std::vector<DescriptorBinding> layout;
  for (uint32_t b :
       {LB_FLIP_BINDING_A, LB_FLIP_BINDING_B, LB_FLIP_BINDING_PLANES, LB_FLIP_BINDING_KERNELS, LB_FLIP_BINDING_MAP})
    layout.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT});
  bindings_ = createBindings(ctx, layout, VK_SHADER_STAGE_COMPUTE_BIT, sizeof(FlipPush));
  rows_ = createComputePipeline(ctx, bindings_.pipelineLayout, "flip_rows");
  cols_ = createComputePipeline(ctx, bindings_.pipelineLayout, "flip_cols");
  combine_ = createComputePipeline(ctx, bindings_.pipelineLayout, "flip_combine");
}

const Buffer& GpuFlip::run(const Buffer& reference, const Buffer& test) {
  const VkDeviceSize need = VkDeviceSize(width_) * VkDeviceSize(height_) * 4;
  if (reference.size < need || test.size < need)
    throw std::invalid_argument("GpuFlip: an input buffer holds fewer than " + std::to_string(need) + " bytes");
  const Buffer* buffers[5] = {&reference, &test, &planes_, &kernelBuffer_, &map_};
  const uint32_t slots[5] = {LB_FLIP_BINDING_A, LB_FLIP_BINDING_B, LB_FLIP_BINDING_PLANES, LB_FLIP_BINDING_KERNELS,
                             LB_FLIP_BINDING_MAP};
  VkDescriptorBufferInfo infos[5];
  VkWriteDescriptorSet writes[5];
  for (int i = 0; i < 5; ++i) {
    infos[i] = {buffers[i]->buffer, 0, VK_WHOLE_SIZE};
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = bindings_.set;
    writes[i].dstBinding = slots[i];
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(ctx_.device, 5, writes, 0, nullptr);
  const uint32_t gx = (uint32_t(width_) + LB_FLIP_GROUP - 1) / LB_FLIP_GROUP;
  const uint32_t gy = (uint32_t(height_) + LB_FLIP_GROUP - 1) / LB_FLIP_GROUP;
  runOneShot(ctx_, [&](VkCommandBuffer cmd) {
    // The inputs were written by earlier submissions; each pass reads what the one before wrote.
    auto barrier = [&](VkPipelineStageFlags2 src) {
      memoryBarrier(cmd, src, VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    };
    barrier(VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, bindings_.pipelineLayout, 0, 1, &bindings_.set, 0,
                            nullptr);
    auto dispatch = [&](VkPipeline pipeline, uint32_t image) {
      FlipPush push{uint32_t(width_),
                    uint32_t(height_),
                    uint32_t(kernels_.csfRadius),
                    uint32_t(kernels_.featureRadius),
                    image,
                    0,
                    0,
                    0};
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
      vkCmdPushConstants(cmd, bindings_.pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
      vkCmdDispatch(cmd, gx, gy, 1);
    };
    dispatch(rows_, 0);
    dispatch(rows_, 1);
    barrier(VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    dispatch(cols_, 0);
    dispatch(cols_, 1);
    barrier(VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    dispatch(combine_, 0);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
  });
  return map_;
}

}  // namespace lb
