// Query pools of the frame ring: three timestamps (top, LOD done, bottom) and one statistics query per slot.
#include "render/gpu_profiler.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "vk/context.h"
#include "vk/vk_check.h"

namespace lb {

namespace {
enum Query : uint32_t { kQueryTop = 0, kQueryBottom = 1, kQueryLod = 2, kTimestampsPerSlot = 3 };
}

uint64_t timestampMaskFromValidBits(uint32_t validBits) {
  if (validBits == 0) return 0;
  return validBits >= 64 ? ~0ull : (1ull << validBits) - 1;
}

uint64_t queueTimestampMask(const Context& ctx) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice, &n, families.data());
  return ctx.queueFamily < n ? timestampMaskFromValidBits(families[ctx.queueFamily].timestampValidBits) : 0;
}

PassTimer::PassTimer(Context& ctx) : ctx_(ctx), mask_(queueTimestampMask(ctx)) {
  VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qi.queryCount = 2;
  VkQueryPool pool;
  VK_CHECK(vkCreateQueryPool(ctx.device, &qi, nullptr, &pool));
  pool_ = vk::Unique(ctx.device, pool);
}

void PassTimer::begin(VkCommandBuffer cmd) {
  if (mask_ == 0) return;
  vkCmdResetQueryPool(cmd, pool_, 0, 2);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, pool_, 0);
}

void PassTimer::end(VkCommandBuffer cmd) {
  if (mask_ != 0) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, 1);
}

double PassTimer::ms() {
  uint64_t ts[2] = {};
  if (mask_ == 0 || vkGetQueryPoolResults(ctx_.device, pool_, 0, 2, sizeof ts, ts, sizeof ts[0],
                                          VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT) != VK_SUCCESS)
    return std::nan("");
  return double((ts[1] - ts[0]) & mask_) * double(ctx_.props.limits.timestampPeriod) * 1e-6;
}

GpuProfiler::GpuProfiler(Context& ctx, int slots)
    : ctx_(ctx), lodWritten_(size_t(slots), false), meshWatched_(size_t(slots), false) {
  mask_ = queueTimestampMask(ctx);
  periodNs_ = double(ctx.props.limits.timestampPeriod);
  VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qi.queryCount = uint32_t(slots) * kTimestampsPerSlot;
  VkQueryPool pool;
  VK_CHECK(vkCreateQueryPool(ctx_.device, &qi, nullptr, &pool));
  timestamps_ = vk::Unique(ctx_.device, pool);
  qi.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
  qi.queryCount = uint32_t(slots);
  qi.pipelineStatistics = VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_VERTICES_BIT |
                          VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_PRIMITIVES_BIT |
                          VK_QUERY_PIPELINE_STATISTIC_VERTEX_SHADER_INVOCATIONS_BIT |
                          VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_CONTROL_SHADER_PATCHES_BIT |
                          VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_EVALUATION_SHADER_INVOCATIONS_BIT |
                          VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT |
                          VK_QUERY_PIPELINE_STATISTIC_CLIPPING_PRIMITIVES_BIT |
                          VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT;
  VK_CHECK(vkCreateQueryPool(ctx_.device, &qi, nullptr, &pool));
  stats_ = vk::Unique(ctx_.device, pool);
  if (ctx.meshShader) {
    qi.pipelineStatistics = VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT |
                            VK_QUERY_PIPELINE_STATISTIC_CLIPPING_PRIMITIVES_BIT |
                            VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT;
    if (ctx.meshShaderQueries)
      qi.pipelineStatistics |= VK_QUERY_PIPELINE_STATISTIC_TASK_SHADER_INVOCATIONS_BIT_EXT |
                               VK_QUERY_PIPELINE_STATISTIC_MESH_SHADER_INVOCATIONS_BIT_EXT;
    VK_CHECK(vkCreateQueryPool(ctx_.device, &qi, nullptr, &pool));
    meshStats_ = vk::Unique(ctx_.device, pool);
  }
}

void GpuProfiler::reset(VkCommandBuffer cmd, int slot) {
  vkCmdResetQueryPool(cmd, timestamps_, uint32_t(slot) * kTimestampsPerSlot, kTimestampsPerSlot);
  vkCmdResetQueryPool(cmd, stats_, uint32_t(slot), 1);
  if (meshStats_) vkCmdResetQueryPool(cmd, meshStats_, uint32_t(slot), 1);
  lodWritten_[size_t(slot)] = false;
  meshWatched_[size_t(slot)] = false;
}

void GpuProfiler::timestampLod(VkCommandBuffer cmd, int slot) {
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, timestamps_,
                       uint32_t(slot) * kTimestampsPerSlot + kQueryLod);
  lodWritten_[size_t(slot)] = true;
}

void GpuProfiler::timestampTop(VkCommandBuffer cmd, int slot) {
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, timestamps_,
                       uint32_t(slot) * kTimestampsPerSlot + kQueryTop);
}

void GpuProfiler::timestampBottom(VkCommandBuffer cmd, int slot) {
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, timestamps_,
                       uint32_t(slot) * kTimestampsPerSlot + kQueryBottom);
}

void GpuProfiler::beginStats(VkCommandBuffer cmd, int slot, bool meshStages) {
  if (meshStages && !meshStats_) throw std::logic_error("GpuProfiler: mesh-shader draws on a device without them");
  meshWatched_[size_t(slot)] = meshStages;
  vkCmdBeginQuery(cmd, meshStages ? meshStats_ : stats_, uint32_t(slot), 0);
}
void GpuProfiler::endStats(VkCommandBuffer cmd, int slot) {
  vkCmdEndQuery(cmd, meshWatched_[size_t(slot)] ? meshStats_ : stats_, uint32_t(slot));
}

GpuSample GpuProfiler::read(int slot) {
  // An unwritten query would never become available: read the LOD timestamp only when written.
  const uint32_t n = lodWritten_[size_t(slot)] ? kTimestampsPerSlot : kQueryLod;
  uint64_t ts[kTimestampsPerSlot] = {};
  VK_CHECK(vkGetQueryPoolResults(ctx_.device, timestamps_, uint32_t(slot) * kTimestampsPerSlot, n, n * sizeof(uint64_t),
                                 ts, sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  GpuSample s;
  if (meshWatched_[size_t(slot)]) {
    // In the order of the statistic bits: clipping (0x20, 0x40), FS (0x80), task (0x800), mesh (0x1000).
    uint64_t ms[5] = {};
    const uint32_t n = ctx_.meshShaderQueries ? 5 : 3;
    VK_CHECK(vkGetQueryPoolResults(ctx_.device, meshStats_, uint32_t(slot), 1, n * sizeof(uint64_t), ms,
                                   n * sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    s.stats.clipInvocations = ms[0];
    s.stats.clipPrimitives = ms[1];
    s.stats.fsInvocations = ms[2];
    s.stats.taskInvocations = ms[3];
    s.stats.meshInvocations = ms[4];
  }
  uint64_t st[8] = {};
  if (!meshWatched_[size_t(slot)])
    VK_CHECK(vkGetQueryPoolResults(ctx_.device, stats_, uint32_t(slot), 1, sizeof st, st, sizeof st,
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  s.gpuMs = double((ts[kQueryBottom] - ts[kQueryTop]) & mask_) * periodNs_ * 1e-6;
  if (n == kTimestampsPerSlot) {
    s.lodMs = double((ts[kQueryLod] - ts[kQueryTop]) & mask_) * periodNs_ * 1e-6;
    s.drawMs = double((ts[kQueryBottom] - ts[kQueryLod]) & mask_) * periodNs_ * 1e-6;
  }
  // Results come in the order of the statistic bits: IA, VS, clipping (0x20, 0x40), FS (0x80),
  // then tessellation control (0x100) and evaluation (0x200).
  if (meshWatched_[size_t(slot)]) return s;
  s.stats.iaVertices = st[0];
  s.stats.iaPrimitives = st[1];
  s.stats.vsInvocations = st[2];
  s.stats.clipInvocations = st[3];
  s.stats.clipPrimitives = st[4];
  s.stats.fsInvocations = st[5];
  s.stats.tcsPatches = st[6];
  s.stats.tesInvocations = st[7];
  return s;
}

}  // namespace lb
