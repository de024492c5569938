// Image and error statistics reduced on the GPU: pipelines, one command buffer reused per call, and
// the host's last step (64-bit sums, histogram percentiles, partial sums) on the words read back.
#include "metrics/gpu_reduce.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "render/gpu_profiler.h"
#include "render/pipeline.h"
#include "shaders/reduce_params.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace lb {

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr uint32_t kPixelsPerImageGroup = LB_RED_IMAGE_GROUP * LB_RED_IMAGE_PER_THREAD;
constexpr uint32_t kValuesPerErrorGroup = LB_RED_IMAGE_GROUP * LB_RED_ERROR_PER_THREAD;

uint32_t groups(uint64_t n, uint32_t per) {
  return uint32_t((n + per - 1) / per);
}

struct Weights {  // std430 of reduce_ssim.glsl's Weights block
  float f[16];
  double d[16];
};

}  // namespace

GpuReduce::GpuReduce(Context& ctx, int width, int height, bool allowFloat64)
    : ctx_(ctx),
      width_(width),
      height_(height),
      float64_(allowFloat64 && ctx.enabledFeatures.shaderFloat64),
      timer_(ctx) {
  const uint64_t n = uint64_t(std::max(width, 0)) * uint64_t(std::max(height, 0));
  // The p95 pass ranks values with 95 (n - 1) in 32 bits (reduce_error_select.comp).
  if (width <= 0 || height <= 0 || n * 95 >= (uint64_t(1) << 32))
    throw std::invalid_argument("GpuReduce: " + std::to_string(width) + "x" + std::to_string(height) +
                                " is outside 1 to 45,210,182 pixels");
  imageGroups_ = groups(n, kPixelsPerImageGroup);
  errorGroups_ = groups(n, kValuesPerErrorGroup);
  if (width > 2 * LB_SSIM_RADIUS && height > 2 * LB_SSIM_RADIUS) {
    ssimGroupsX_ = groups(uint32_t(width - 2 * LB_SSIM_RADIUS), LB_RED_SSIM_TILE);
    ssimGroupsY_ = groups(uint32_t(height - 2 * LB_SSIM_RADIUS), LB_RED_SSIM_TILE);
  }
  const uint32_t partialWords = std::max(errorGroups_, ssimGroupsX_ * ssimGroupsY_ * (float64_ ? 2 : 1));
  const VkDeviceSize bytes = VkDeviceSize(LB_RED_PARTIALS + partialWords) * 4;
  result_ = createBuffer(
      ctx, bytes,
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false,
      {GpuResource::Measure});
  readback_ = createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, {GpuResource::Measure});
  Weights w{};
  const SsimConstants& k = ssimConstants();
  for (int i = 0; i <= 2 * LB_SSIM_RADIUS; ++i) w.d[i] = k.window[i];
  for (int i = 0; i < 3; ++i) w.d[LB_SSIM_LUMA + i] = k.luma[i];
  w.d[LB_SSIM_C1] = k.c1;
  w.d[LB_SSIM_C2] = k.c2;
  for (int i = 0; i < 16; ++i) w.f[i] = float(w.d[i]);
  weights_ = createBufferWithData(ctx, &w, sizeof w, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, {GpuResource::Measure});

  std::vector<DescriptorBinding> layout;
  for (uint32_t b : {LB_REDUCE_BINDING_A, LB_REDUCE_BINDING_B, LB_REDUCE_BINDING_RESULT, LB_REDUCE_BINDING_WEIGHTS})
    layout.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT});
  bindings_ = createBindings(ctx, layout, VK_SHADER_STAGE_COMPUTE_BIT, sizeof(ReducePush));
  VkDescriptorBufferInfo infos[2] = {{result_.buffer, 0, VK_WHOLE_SIZE}, {weights_.buffer, 0, VK_WHOLE_SIZE}};
  VkWriteDescriptorSet writes[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
  for (int i = 0; i < 2; ++i) {
    writes[i].dstSet = bindings_.set;
    writes[i].dstBinding = i == 0 ? LB_REDUCE_BINDING_RESULT : LB_REDUCE_BINDING_WEIGHTS;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(ctx.device, 2, writes, 0, nullptr);

  image_ = createComputePipeline(ctx, bindings_.pipelineLayout, "reduce_image");
  ssim_ = createComputePipeline(ctx, bindings_.pipelineLayout, float64_ ? "reduce_ssim_f64" : "reduce_ssim");
  error_ = createComputePipeline(ctx, bindings_.pipelineLayout, "reduce_error");
  select_ = createComputePipeline(ctx, bindings_.pipelineLayout, "reduce_error_select");
  fine_ = createComputePipeline(ctx, bindings_.pipelineLayout, "reduce_error_fine");

  fence_ = createFence(ctx);
  pool_ = createCommandPool(ctx, &cmd_, 1);
}

Buffer GpuReduce::upload(const RgbaImage& img) {
  if (img.px.empty()) throw std::invalid_argument("GpuReduce::upload: empty image");
  return createBufferWithData(ctx_, img.px.data(), img.px.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              {GpuResource::Measure});
}

Buffer GpuReduce::upload(const std::vector<float>& v) {
  if (v.empty()) throw std::invalid_argument("GpuReduce::upload: empty error map");
  return createBufferWithData(ctx_, v.data(), v.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              {GpuResource::Measure});
}

void GpuReduce::bind(const Buffer& a, const Buffer& b) {
  const VkDeviceSize need = VkDeviceSize(width_) * VkDeviceSize(height_) * 4;
  if (a.size < need || b.size < need)
    throw std::invalid_argument("GpuReduce: an input buffer holds " + std::to_string(std::min(a.size, b.size)) +
                                " bytes, " + std::to_string(width_) + "x" + std::to_string(height_) + " needs " +
                                std::to_string(need));
  VkDescriptorBufferInfo infos[2] = {{a.buffer, 0, VK_WHOLE_SIZE}, {b.buffer, 0, VK_WHOLE_SIZE}};
  VkWriteDescriptorSet writes[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
  for (int i = 0; i < 2; ++i) {
    writes[i].dstSet = bindings_.set;
    writes[i].dstBinding = i == 0 ? LB_REDUCE_BINDING_A : LB_REDUCE_BINDING_B;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(ctx_.device, 2, writes, 0, nullptr);
}

void GpuReduce::dispatch(VkCommandBuffer cmd, VkPipeline pipeline, uint32_t x, uint32_t y, const ReducePush& push) {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  vkCmdPushConstants(cmd, bindings_.pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
  vkCmdDispatch(cmd, x, y, 1);
}

void GpuReduce::run(uint32_t partialWords, const std::function<void(VkCommandBuffer)>& passes) {
  VK_CHECK(vkResetFences(ctx_.device, 1, fence_.ptr()));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd_, &bi));
  timer_.begin(cmd_);
  // The inputs were written by earlier submissions (renders, uploads); the words need clearing.
  memoryBarrier(cmd_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
  vkCmdFillBuffer(cmd_, result_.buffer, 0, LB_RED_PARTIALS * 4, 0);
  memoryBarrier(cmd_, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindDescriptorSets(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, bindings_.pipelineLayout, 0, 1, &bindings_.set, 0,
                          nullptr);
  passes(cmd_);
  memoryBarrier(cmd_, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  const VkDeviceSize header = LB_RED_PARTIALS * 4;
  VkBufferCopy regions[2] = {{0, 0, header}, {header, header, VkDeviceSize(partialWords) * 4}};
  vkCmdCopyBuffer(cmd_, result_.buffer, readback_.buffer, partialWords > 0 ? 2 : 1, regions);
  memoryBarrier(cmd_, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  timer_.end(cmd_);
  VK_CHECK(vkEndCommandBuffer(cmd_));
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd_;
  VK_CHECK(vkQueueSubmit(ctx_.queue, 1, &si, fence_));
  try {
    VK_CHECK(vkWaitForFences(ctx_.device, 1, fence_.ptr(), VK_TRUE, UINT64_MAX));
  } catch (...) {
    vkQueueWaitIdle(ctx_.queue);  // the work must end before its buffers can go
    throw;
  }
  lastGpuMs_ = timer_.ms();
  words_.resize(LB_RED_PARTIALS + partialWords);
  std::memcpy(words_.data(), readback_.mapped, words_.size() * 4);
}

}  // namespace lb
