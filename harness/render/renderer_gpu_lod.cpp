// The renderer's GPU-indirect path (render/instanced.h GpuLod): the scheme's compute passes write
// instances and indirect draw arguments every frame on a state buffer that persists across frames;
// the hooks reset, snapshot and restore that state.
#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "error.h"
#include "render/pipeline.h"
#include "render/renderer.h"
#include "shaders/shared.h"
#include "vk/context.h"
#include "vk/device_limits.h"
#include "vk/resources.h"
#include "vk/vk_check.h"

namespace lb {

void Renderer::createGpuLod() {
  const std::string& name = scheme_->info().name;
  // The view budget is the LOD viewport (the case's resolution wherever the two differ); the
  // records live in one storage buffer of one allocation, written by one dispatch per pass.
  GpuLodBudget budget;
  budget.viewportWidth = uint32_t(settings_.lodWidth > 0 ? settings_.lodWidth : settings_.width);
  budget.viewportHeight = uint32_t(settings_.lodHeight > 0 ? settings_.lodHeight : settings_.height);
  budget.maxRecordBytes =
      std::min<uint64_t>(ctx_.props.limits.maxStorageBufferRange, deviceLimits(ctx_.physicalDevice).maxAllocationBytes);
  budget.maxDispatchGroups = ctx_.props.limits.maxComputeWorkGroupCount[0];
  gpuLod_ = scheme_->gpuLod(terrain_, params_, budget);
  const Footprint& f = gpuLod_.footprint;
  const bool tessellated = !scheme_->info().tesc.empty();  // one patch a leaf (cbt-ts)
  if (f.indices.empty() || f.indices.size() % 3 != 0 || gpuLod_.maxInstances == 0 || gpuLod_.passes.empty() ||
      gpuLod_.initialState.empty() || gpuLod_.maxDraws == 0)
    throw std::logic_error("scheme '" + name +
                           "' is GPU-indirect but supplies no footprint, state, capacity or passes");
  for (uint32_t i : f.indices)
    if (i >= f.vertices.size()) throw std::logic_error("scheme '" + name + "': footprint index out of range");
  if (gpuLod_.maxDraws > 1 && (!ctx_.drawIndirectCount || !ctx_.enabledFeatures.multiDrawIndirect ||
                               !ctx_.enabledFeatures.drawIndirectFirstInstance))
    throw FeatureMissing("scheme '" + name +
                         "' draws with vkCmdDrawIndexedIndirectCount: the device lacks drawIndirectCount, "
                         "multiDrawIndirect or drawIndirectFirstInstance");
  footprintRanges_ = {{0, uint32_t(f.indices.size()), 0}};
  controlPoints_ = tessellated ? 3 : controlPoints_;
  auto bytes = [](const auto& v) { return VkDeviceSize(v.size() * sizeof(v[0])); };
  vertices_ = createBufferWithData(ctx_, f.vertices.data(), bytes(f.vertices), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  indices_ = createBufferWithData(ctx_, f.indices.data(), bytes(f.indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  minimalPatchBuffers();
  instanceCapacity_ = gpuLod_.maxInstances;
  instances_ = createBuffer(ctx_, VkDeviceSize(sizeof(InstanceRecord)) * instanceCapacity_,
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
  // Indirect too: a pass may dispatch the next by counts an earlier one wrote into the state.
  const VkBufferUsageFlags state = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  lodState_ = createBufferWithData(ctx_, gpuLod_.initialState.data(), bytes(gpuLod_.initialState), state);
  lodSnapshot_ = createBuffer(ctx_, bytes(gpuLod_.initialState), state, false);
  // Zeros until the first pass writes them: an empty draw, never garbage counts.
  const std::vector<uint32_t> noDraw(argsWords(), 0u);
  lodArgs_ = createBufferWithData(
      ctx_, noDraw.data(), noDraw.size() * sizeof(uint32_t),
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  // Every slot's arguments, then the overflow word updateLod copies (GpuLod::overflowWord).
  lodArgsReadback_ =
      createBuffer(ctx_, (noDraw.size() * kSlots + 1) * sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  std::memset(lodArgsReadback_.mapped, 0, size_t(lodArgsReadback_.size));
  for (const GpuLodPass& pass : gpuLod_.passes) {
    if (pass.indirectWord >= 0 && uint64_t(pass.indirectWord + 3) > gpuLod_.initialState.size())
      throw std::logic_error("scheme '" + name + "': indirect dispatch arguments outside the state");
    const uint32_t spec = uint32_t(pass.spec);
    lodPipelines_.push_back(
        createComputePipeline(ctx_, bindings_.pipelineLayout, pass.shader, pass.spec >= 0 ? &spec : nullptr));
  }
  gpuIndirect_ = true;
  lodFrozen_ = false;
  lastLodInstances_ = lastLodOverflow_ = 0;
  if (gpuLod_.overflowWord >= int64_t(gpuLod_.initialState.size()) ||
      gpuLod_.capacityWord >= int64_t(gpuLod_.initialState.size()))
    throw std::logic_error("scheme '" + name + "': overflow or capacity word outside the state");
  if (VkDeviceSize(sizeof(InstanceRecord)) * gpuLod_.maxInstances > budget.maxRecordBytes)
    throw std::logic_error("scheme '" + name + "': " + std::to_string(gpuLod_.maxInstances) +
                           " instance records exceed the device's largest storage buffer");
}

void Renderer::recordLodPasses(VkCommandBuffer cmd, uint32_t dynOffset) {
  // The previous frame's draw still reads the instances and arguments these passes rewrite.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  // No push constants here: the passes read none (DrawPush is the tessellation path's), and Mesa
  // 22.3 lavapipe crashes in a dispatch that follows a push-constant update naming the compute stage
  // (measured: an empty compute shader crashed with the update, ran without it).
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, bindings_.pipelineLayout, 0, 1, &bindings_.set, 1,
                          &dynOffset);
  for (size_t k = 0; k < lodPipelines_.size(); ++k) {
    if (k > 0)
      memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                        VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, lodPipelines_[k]);
    const GpuLodPass& pass = gpuLod_.passes[k];
    if (pass.indirectWord >= 0)
      vkCmdDispatchIndirect(cmd, lodState_.buffer, VkDeviceSize(pass.indirectWord) * sizeof(uint32_t));
    else
      vkCmdDispatch(cmd, pass.groups, 1, 1);
  }
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT,
                VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

size_t Renderer::argsWords() const {
  return gpuLod_.maxDraws == 1 ? 5 : 5 * size_t(gpuLod_.maxDraws) + 1;
}

void Renderer::drawLod(VkCommandBuffer cmd) {
  constexpr uint32_t stride = 5 * sizeof(uint32_t);
  if (gpuLod_.maxDraws == 1)
    vkCmdDrawIndexedIndirect(cmd, lodArgs_.buffer, 0, 1, stride);
  else
    vkCmdDrawIndexedIndirectCount(cmd, lodArgs_.buffer, 0, lodArgs_.buffer, VkDeviceSize(gpuLod_.maxDraws) * stride,
                                  gpuLod_.maxDraws, stride);
}

void Renderer::copyLodArgs(VkCommandBuffer cmd, int slotIndex) {
  const VkDeviceSize bytes = argsWords() * sizeof(uint32_t);
  VkBufferCopy region{0, VkDeviceSize(slotIndex) * bytes, bytes};
  vkCmdCopyBuffer(cmd, lodArgs_.buffer, lodArgsReadback_.buffer, 1, &region);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                VK_ACCESS_2_HOST_READ_BIT);
}

Renderer::LodDrawn Renderer::lodDrawn(int slotIndex) const {
  const auto* a = static_cast<const uint32_t*>(lodArgsReadback_.mapped) + size_t(slotIndex) * argsWords();
  LodDrawn out;
  out.draws = gpuLod_.maxDraws == 1 ? 1 : std::min(a[5 * gpuLod_.maxDraws], gpuLod_.maxDraws);
  for (uint32_t k = 0; k < out.draws; ++k) out.instances += a[5 * k + 1];
  return out;
}

void Renderer::copyLodState(const Buffer& from, const Buffer& to) {
  if (!gpuIndirect_) throw std::logic_error("LOD state hooks: the scheme is not GPU-indirect");
  finish();
  runOneShot(ctx_, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, from.size};
    vkCmdCopyBuffer(cmd, from.buffer, to.buffer, 1, &region);
  });
}

void Renderer::resetLodState() {
  if (!gpuIndirect_) throw std::logic_error("LOD state hooks: the scheme is not GPU-indirect");
  finish();
  Buffer initial = createBufferWithData(ctx_, gpuLod_.initialState.data(),
                                        VkDeviceSize(gpuLod_.initialState.size() * sizeof(uint32_t)),
                                        VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  copyLodState(initial, lodState_);
}

void Renderer::snapshotLodState() {
  copyLodState(lodState_, lodSnapshot_);
}

void Renderer::restoreLodState() {
  copyLodState(lodSnapshot_, lodState_);
}

void Renderer::loadLodState(const std::vector<uint32_t>& words) {
  if (!gpuIndirect_) throw std::logic_error("LOD state hooks: the scheme is not GPU-indirect");
  if (words.size() != gpuLod_.initialState.size())
    throw std::logic_error("loadLodState: " + std::to_string(words.size()) + " words, the state has " +
                           std::to_string(gpuLod_.initialState.size()));
  if (gpuLod_.capacityWord >= 0 && words[size_t(gpuLod_.capacityWord)] > gpuLod_.maxInstances)
    throw std::logic_error("loadLodState: the state claims room for " +
                           std::to_string(words[size_t(gpuLod_.capacityWord)]) + " instances, this renderer holds " +
                           std::to_string(gpuLod_.maxInstances));
  finish();
  Buffer from = createBufferWithData(ctx_, words.data(), VkDeviceSize(words.size() * sizeof(uint32_t)),
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  copyLodState(from, lodState_);
}

uint32_t Renderer::updateLod(const CameraPose& pose) {
  if (!gpuIndirect_) throw std::logic_error("updateLod: the scheme is not GPU-indirect");
  finish();
  // The passes read the frame uniforms of a slot like a frame's; no frame is in flight to share it.
  const int si = nextSlot_;
  const bool frozen = lodFrozen_;
  lodFrozen_ = false;
  fillUniforms(si, pose, pose);
  lodFrozen_ = frozen;
  runOneShot(ctx_, [&](VkCommandBuffer cmd) {
    recordLodPasses(cmd, uint32_t(uniformStride_ * VkDeviceSize(si)));
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    copyLodArgs(cmd, si);
    if (gpuLod_.overflowWord >= 0) {
      VkBufferCopy word{VkDeviceSize(gpuLod_.overflowWord) * sizeof(uint32_t),
                        VkDeviceSize(argsWords() * kSlots) * sizeof(uint32_t), sizeof(uint32_t)};
      vkCmdCopyBuffer(cmd, lodState_.buffer, lodArgsReadback_.buffer, 1, &word);
      memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                    VK_ACCESS_2_HOST_READ_BIT);
    }
  });
  lastLodInstances_ = lodDrawn(si).instances;
  lastLodOverflow_ =
      gpuLod_.overflowWord >= 0 ? static_cast<const uint32_t*>(lodArgsReadback_.mapped)[argsWords() * kSlots] : 0;
  return lastLodInstances_;
}

std::vector<uint32_t> Renderer::readLodState() {
  if (!gpuIndirect_) throw std::logic_error("LOD state hooks: the scheme is not GPU-indirect");
  finish();
  Buffer host = createBuffer(ctx_, lodState_.size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  copyLodState(lodState_, host);
  const auto* p = static_cast<const uint32_t*>(host.mapped);
  return std::vector<uint32_t>(p, p + gpuLod_.initialState.size());
}

}  // namespace lb
