#pragma once
// GPU timestamps and pipeline statistics of a ring of frames in flight, in one place: the
// renderer records begin/end around its draws and reads a slot back after that slot's fence.
// The probe (render/probe.h) uses the same unit, so both sides of a comparison time alike.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "render/frame_data.h"
#include "vk/unique.h"

namespace lb {

struct Context;

struct GpuSample {
  double gpuMs = 0;  // closing minus opening timestamp, masked to the valid bits, x timestampPeriod
  // With a LOD timestamp written (timestampLod): opening to LOD (the LOD work on the GPU) and LOD to
  // closing (drawing); -1 without one (the tessellation path decides LOD inside its draws).
  double lodMs = -1, drawMs = -1;
  PipelineStats stats;
};

class GpuProfiler {
 public:
  GpuProfiler(Context& ctx, int slots);
  GpuProfiler(const GpuProfiler&) = delete;
  GpuProfiler& operator=(const GpuProfiler&) = delete;

  // Outside a render pass: resets the slot's queries.
  void reset(VkCommandBuffer cmd, int slot);
  void timestampTop(VkCommandBuffer cmd, int slot);
  void timestampBottom(VkCommandBuffer cmd, int slot);
  // Between the LOD work and the draws (draw paths whose LOD runs apart from drawing).
  void timestampLod(VkCommandBuffer cmd, int slot);
  // `meshStages`: the draws run task and mesh shaders, which a query counting input assembly,
  // vertex or tessellation work must not watch; they get a query of their own statistics.
  void beginStats(VkCommandBuffer cmd, int slot, bool meshStages = false);
  void endStats(VkCommandBuffer cmd, int slot);
  // After the slot's fence: waits for its results (they are available by then).
  GpuSample read(int slot);

 private:
  Context& ctx_;
  vk::Unique<VkQueryPool> timestamps_, stats_;
  vk::Unique<VkQueryPool> meshStats_;  // where the device has mesh shaders: clipping, fragments, task and mesh
  uint64_t mask_ = 0;                  // the bits the queue's timestamps carry (timestampValidBits; 0: none)
  double periodNs_ = 0;
  std::vector<bool> lodWritten_;
  std::vector<bool> meshWatched_;  // per slot: its statistics are in meshStats_
};

// Timestamp mask from a queue family's timestampValidBits (64 -> all bits, 0 -> none).
uint64_t timestampMaskFromValidBits(uint32_t validBits);
// The context's queue family's mask: wrap-around of its timestamps is masked with it.
uint64_t queueTimestampMask(const Context& ctx);

// GPU time of one pass outside the timed frames (a measurement compute pass): begin() and end()
// bracket it in its command buffer, ms() reads it after the submission completed; NaN where the
// queue has no timestamp bits (then nothing is written).
class PassTimer {
 public:
  explicit PassTimer(Context& ctx);
  void begin(VkCommandBuffer cmd);
  void end(VkCommandBuffer cmd);
  double ms();

 private:
  Context& ctx_;
  vk::Unique<VkQueryPool> pool_;
  uint64_t mask_ = 0;
};

}  // namespace lb
