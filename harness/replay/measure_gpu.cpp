#include "replay/measure_gpu.h"

#include <cstring>

#include "replay/timing_passes.h"
#include "terrain/heightfield.h"
#include "vk/context.h"

namespace lb {

bool measureOnGpu(const MeasureSpec& spec, const Context& ctx) {
  if (spec.compute == "gpu") return true;
  if (spec.compute == "cpu") return false;
  return !cpuRasterizer(ctx);
}

static Buffer frameBuffer(Context& ctx, int width, int height) {
  return createBuffer(
      ctx, VkDeviceSize(width) * VkDeviceSize(height) * 4,
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false,
      {GpuResource::Measure});
}

MeasureGpu::MeasureGpu(Context& ctx, int width, int height)
    : reduce(ctx, width, height),
      shaded(frameBuffer(ctx, width, height)),
      truth(frameBuffer(ctx, width, height)),
      error(frameBuffer(ctx, width, height)),
      popFrozen(frameBuffer(ctx, width, height)),
      popLive(frameBuffer(ctx, width, height)),
      surplusError(frameBuffer(ctx, width, height)),
      ctx_(ctx),
      width_(width),
      height_(height) {
  staging_ = createBuffer(ctx, VkDeviceSize(width) * VkDeviceSize(height) * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true,
                          {GpuResource::Measure});
}

void MeasureGpu::castTruth(const Heightfield& terrain, const CameraPose& pose) {
  if (haveTruth_ && pose.eye == truthPose_.eye && pose.target == truthPose_.target && pose.fovDeg == truthPose_.fovDeg)
    return;
  haveTruth_ = false;  // stays false if the ray cast throws
  if (!raycast_) raycast_ = std::make_unique<GpuRaycast>(ctx_, terrain);
  raycast_->run(pose, width_, height_, truth, nullptr);
  truthPose_ = pose;
  haveTruth_ = true;
}

static void readBack(Context& ctx, const Buffer& from, const Buffer& to) {
  runOneShot(ctx, [&](VkCommandBuffer cmd) {
    // Written by a compute pass or the renderer's copy in an earlier submission.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                  VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferCopy region{0, 0, to.size};
    vkCmdCopyBuffer(cmd, from.buffer, to.buffer, 1, &region);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                  VK_ACCESS_2_HOST_READ_BIT);
  });
}

RgbaImage MeasureGpu::readImage(const Buffer& b) {
  readBack(ctx_, b, staging_);
  const auto* p = static_cast<const uint8_t*>(staging_.mapped);
  return {width_, height_, std::vector<uint8_t>(p, p + staging_.size)};
}

std::vector<float> MeasureGpu::readFloats(const Buffer& b) {
  readBack(ctx_, b, staging_);
  std::vector<float> v(size_t(width_) * size_t(height_));
  std::memcpy(v.data(), staging_.mapped, v.size() * sizeof(float));
  return v;
}

GpuFlip& MeasureGpu::flip(double ppd) {
  if (!flip_ || flip_->ppd() != ppd) flip_ = std::make_unique<GpuFlip>(ctx_, width_, height_, ppd);
  return *flip_;
}

}  // namespace lb
