// The GPU-indirect path (render/instanced.h GpuLod): the scheme's compute passes write instances
// and indirect draw arguments every frame on a state buffer that persists across frames; the LOD
// state hooks (render/lod_state.h) reset, snapshot, restore, update and freeze that state.
#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "error.h"
#include "render/lod_state.h"
#include "render/path_drawer.h"
#include "render/pipeline.h"
#include "shaders/shared.h"
#include "vk/context.h"
#include "vk/device_limits.h"
#include "vk/resources.h"

namespace lb {
namespace {

class GpuIndirectDrawer : public PathDrawer, public LodState {
 public:
  explicit GpuIndirectDrawer(const PathEnv& env) : env_(env) {
    Context& ctx = env.ctx;
    const std::string& name = env.scheme.info().name;
    // The view budget is the LOD viewport (the case's resolution wherever the two differ); the
    // records live in one storage buffer of one allocation, written by one dispatch per pass.
    GpuLodBudget budget;
    budget.viewportWidth = uint32_t(env.settings.lodWidth > 0 ? env.settings.lodWidth : env.settings.width);
    budget.viewportHeight = uint32_t(env.settings.lodHeight > 0 ? env.settings.lodHeight : env.settings.height);
    budget.maxRecordBytes =
        std::min<uint64_t>(ctx.props.limits.maxStorageBufferRange, deviceLimits(ctx.physicalDevice).maxAllocationBytes);
    budget.maxDispatchGroups = ctx.props.limits.maxComputeWorkGroupCount[0];
    lod_ = env.scheme.gpuLod(env.terrain, env.params, budget);
    const Footprint& f = lod_.footprint;
    if (f.indices.empty() || f.indices.size() % 3 != 0 || lod_.maxInstances == 0 || lod_.passes.empty() ||
        lod_.initialState.empty() || lod_.maxDraws == 0)
      throw std::logic_error("scheme '" + name +
                             "' is GPU-indirect but supplies no footprint, state, capacity or passes");
    for (uint32_t i : f.indices)
      if (i >= f.vertices.size()) throw std::logic_error("scheme '" + name + "': footprint index out of range");
    // The device feature this path may need beyond the core's.
    if (lod_.maxDraws > 1 && (!ctx.drawIndirectCount || !ctx.enabledFeatures.multiDrawIndirect ||
                              !ctx.enabledFeatures.drawIndirectFirstInstance))
      throw FeatureMissing("scheme '" + name +
                           "' draws with vkCmdDrawIndexedIndirectCount: the device lacks drawIndirectCount, "
                           "multiDrawIndirect or drawIndirectFirstInstance");
    auto bytes = [](const auto& v) { return VkDeviceSize(v.size() * sizeof(v[0])); };
    vertices_ = createBufferWithData(ctx, f.vertices.data(), bytes(f.vertices), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                                     {GpuResource::Geometry, env.memory});
    indices_ = createBufferWithData(ctx, f.indices.data(), bytes(f.indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                                    {GpuResource::Geometry, env.memory});
    instances_ = createBuffer(ctx, VkDeviceSize(sizeof(InstanceRecord)) * lod_.maxInstances,
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false, {GpuResource::Instances, env.memory});
    // Indirect too: a pass may dispatch the next by counts an earlier one wrote into the state.
    const VkBufferUsageFlags state = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    state_ = createBufferWithData(ctx, lod_.initialState.data(), bytes(lod_.initialState), state,
                                  {GpuResource::LodState, env.memory});
    snapshot_ = createBuffer(ctx, bytes(lod_.initialState), state, false, {GpuResource::LodState, env.memory});
    // Zeros until the first pass writes them: an empty draw, never garbage counts.
    const std::vector<uint32_t> noDraw(argsWords(), 0u);
    args_ = createBufferWithData(
        ctx, noDraw.data(), noDraw.size() * sizeof(uint32_t),
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
        {GpuResource::LodState, env.memory});
    // Every slot's arguments, then the overflow word update() copies (GpuLod::overflowWord).
    argsReadback_ = createBuffer(ctx, (noDraw.size() * size_t(env.slots) + 1) * sizeof(uint32_t),
                                 VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, {GpuResource::Capture, env.memory});
    std::memset(argsReadback_.mapped, 0, size_t(argsReadback_.size));
    for (const GpuLodPass& pass : lod_.passes) {
      if (pass.indirectWord >= 0 && uint64_t(pass.indirectWord + 3) > lod_.initialState.size())
        throw std::logic_error("scheme '" + name + "': indirect dispatch arguments outside the state");
      const uint32_t spec = uint32_t(pass.spec);
      pipelines_.push_back(
          createComputePipeline(ctx, env.bindings.pipelineLayout, pass.shader, pass.spec >= 0 ? &spec : nullptr));
    }
    if (lod_.overflowWord >= int64_t(lod_.initialState.size()) ||
        lod_.capacityWord >= int64_t(lod_.initialState.size()))
      throw std::logic_error("scheme '" + name + "': overflow or capacity word outside the state");
    if (VkDeviceSize(sizeof(InstanceRecord)) * lod_.maxInstances > budget.maxRecordBytes)
      throw std::logic_error("scheme '" + name + "': " + std::to_string(lod_.maxInstances) +
                             " instance records exceed the device's largest storage buffer");
  }

  // A scheme with a control shader (cbt-ts) draws its instances as patches of one triangle.
  GeometryStages stages() const override {
    const SchemeInfo& info = env_.scheme.info();
    GeometryStages s;
    s.vert = info.vert + ".vert.spv";
    if (!info.tesc.empty()) {
      s.tesc = info.tesc + ".tesc.spv";
      s.tese = info.tese + "_" + partitioningName(env_.scheme.partitioning(env_.params)) + ".tese.spv";
      s.controlPoints = 3;
    }
    s.meshCapture = true;
    s.storeStage = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
    return s;
  }
  PathBuffers buffers() const override {
    PathBuffers b;
    b.instances = &instances_;
    b.lodState = &state_;
    b.lodArgs = &args_;
    return b;
  }

  // The GPU decides how many instances: room for as many as the passes may write.
  uint64_t prepare(int /*slot*/, const FrameUniforms& /*u*/, bool /*measured*/) override {
    const uint64_t perInstance =
        lod_.trianglesPerInstance > 0 ? lod_.trianglesPerInstance : lod_.footprint.indices.size() / 3;
    return uint64_t(frozen_ ? lastInstances_ : lod_.maxInstances) * perInstance;
  }

  bool lodApart() const override { return true; }
  void recordLod(VkCommandBuffer cmd, uint32_t dynOffset) override {
    if (!frozen_) recordPasses(cmd, dynOffset);
  }

  void recordDraws(VkCommandBuffer cmd, int /*slot*/) override {
    VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, vertices_.buffer.ptr(), &zero);
    vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
    constexpr uint32_t stride = 5 * sizeof(uint32_t);
    if (lod_.maxDraws == 1)
      vkCmdDrawIndexedIndirect(cmd, args_.buffer, 0, 1, stride);
    else
      vkCmdDrawIndexedIndirectCount(cmd, args_.buffer, 0, args_.buffer, VkDeviceSize(lod_.maxDraws) * stride,
                                    lod_.maxDraws, stride);
  }

  // The arguments the passes wrote, for FrameResult::instances.
  void recordAfterDraws(VkCommandBuffer cmd, int slot) override {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT,
                  VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    copyArgs(cmd, slot);
  }

  void collect(int slot, double /*prepareMs*/, FrameResult& r) const override {
    const Drawn drawn = drawnBy(slot);
    r.instances = drawn.instances;
    r.draws = drawn.draws;
  }
  LodState* lodState() override { return this; }

  // ---- LodState
  void reset() override {
    env_.finish();
    Buffer initial = createBufferWithData(env_.ctx, lod_.initialState.data(),
                                          VkDeviceSize(lod_.initialState.size() * sizeof(uint32_t)),
                                          VK_BUFFER_USAGE_TRANSFER_SRC_BIT, {GpuResource::Staging, env_.memory});
    copyState(initial, state_);
  }
  void snapshot() override { copyState(state_, snapshot_); }
  void restore() override { copyState(snapshot_, state_); }
  std::vector<uint32_t> read() override {
    env_.finish();
    Buffer host = createBuffer(env_.ctx, state_.size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true,
                               {GpuResource::Staging, env_.memory});
    copyState(state_, host);
    const auto* p = static_cast<const uint32_t*>(host.mapped);
    return std::vector<uint32_t>(p, p + lod_.initialState.size());
  }
  void load(const std::vector<uint32_t>& words) override {
    if (words.size() != lod_.initialState.size())
      throw std::logic_error("loadLodState: " + std::to_string(words.size()) + " words, the state has " +
                             std::to_string(lod_.initialState.size()));
    if (lod_.capacityWord >= 0 && words[size_t(lod_.capacityWord)] > lod_.maxInstances)
      throw std::logic_error("loadLodState: the state claims room for " +
                             std::to_string(words[size_t(lod_.capacityWord)]) + " instances, this renderer holds " +
                             std::to_string(lod_.maxInstances));
    env_.finish();
    Buffer from = createBufferWithData(env_.ctx, words.data(), VkDeviceSize(words.size() * sizeof(uint32_t)),
                                       VK_BUFFER_USAGE_TRANSFER_SRC_BIT, {GpuResource::Staging, env_.memory});
    copyState(from, state_);
  }
  void keep() override {
    if (!kept_.buffer)  // made on first use: only a settle series keeps states
      kept_ = createBuffer(env_.ctx, state_.size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           false, {GpuResource::Staging, env_.memory});
    copyState(state_, kept_);
  }
  void putBack() override {
    if (!kept_.buffer) throw std::logic_error("LodState::putBack: nothing kept");
    copyState(kept_, state_);
  }
  uint32_t update(const CameraPose& pose) override {
    env_.finish();
    // The passes read the frame uniforms of a slot like a frame's; no frame is in flight to share it.
    const UniformSlot u = env_.uniforms(pose);
    const size_t overflowAt = argsWords() * size_t(env_.slots);
    runOneShot(env_.ctx, [&](VkCommandBuffer cmd) {
      recordPasses(cmd, u.dynOffset);
      memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
      copyArgs(cmd, u.slot);
      if (lod_.overflowWord >= 0) {
        VkBufferCopy word{VkDeviceSize(lod_.overflowWord) * sizeof(uint32_t),
                          VkDeviceSize(overflowAt) * sizeof(uint32_t), sizeof(uint32_t)};
        vkCmdCopyBuffer(cmd, state_.buffer, argsReadback_.buffer, 1, &word);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                      VK_ACCESS_2_HOST_READ_BIT);
      }
    });
    lastInstances_ = drawnBy(u.slot).instances;
    lastOverflow_ = lod_.overflowWord >= 0 ? static_cast<const uint32_t*>(argsReadback_.mapped)[overflowAt] : 0;
    return lastInstances_;
  }
  void setFrozen(bool frozen) override { frozen_ = frozen; }
  uint32_t overflow() const override { return lastOverflow_; }
  const GpuLod& gpuLod() const override { return lod_; }

 private:
  void recordPasses(VkCommandBuffer cmd, uint32_t dynOffset) {
    // The previous frame's draw still reads the instances and arguments these passes rewrite.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    // No push constants here: the passes read none (DrawPush is the tessellation path's), and Mesa
    // 22.3 lavapipe crashes in a dispatch that follows a push-constant update naming the compute stage
    // (measured: an empty compute shader crashed with the update, ran without it).
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, env_.bindings.pipelineLayout, 0, 1, &env_.bindings.set,
                            1, &dynOffset);
    for (size_t k = 0; k < pipelines_.size(); ++k) {
      if (k > 0)
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                          VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_[k]);
      const GpuLodPass& pass = lod_.passes[k];
      if (pass.indirectWord >= 0)
        vkCmdDispatchIndirect(cmd, state_.buffer, VkDeviceSize(pass.indirectWord) * sizeof(uint32_t));
      else
        vkCmdDispatch(cmd, pass.groups, 1, 1);
    }
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT,
                  VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  }

  // LB_BINDING_LOD_ARGS, in uint32: one command, or maxDraws commands and their count.
  size_t argsWords() const { return lod_.maxDraws == 1 ? 5 : 5 * size_t(lod_.maxDraws) + 1; }

  // Into the slot's region of the readback, for the host.
  void copyArgs(VkCommandBuffer cmd, int slot) {
    const VkDeviceSize bytes = argsWords() * sizeof(uint32_t);
    VkBufferCopy region{0, VkDeviceSize(slot) * bytes, bytes};
    vkCmdCopyBuffer(cmd, args_.buffer, argsReadback_.buffer, 1, &region);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                  VK_ACCESS_2_HOST_READ_BIT);
  }

  struct Drawn {
    uint32_t instances = 0, draws = 0;
  };
  Drawn drawnBy(int slot) const {  // what the slot's copy of the arguments drew
    const auto* a = static_cast<const uint32_t*>(argsReadback_.mapped) + size_t(slot) * argsWords();
    Drawn out;
    out.draws = lod_.maxDraws == 1 ? 1 : std::min(a[5 * lod_.maxDraws], lod_.maxDraws);
    for (uint32_t k = 0; k < out.draws; ++k) out.instances += a[5 * k + 1];
    return out;
  }

  void copyState(const Buffer& from, const Buffer& to) {
    env_.finish();
    runOneShot(env_.ctx, [&](VkCommandBuffer cmd) {
      VkBufferCopy region{0, 0, from.size};
      vkCmdCopyBuffer(cmd, from.buffer, to.buffer, 1, &region);
    });
  }

  PathEnv env_;
  GpuLod lod_;
  std::vector<vk::Unique<VkPipeline>> pipelines_;  // the passes'
  Buffer vertices_, indices_, instances_;
  Buffer state_, snapshot_, args_, argsReadback_;  // argsReadback_: a copy of args_ per slot, for the host
  Buffer kept_;                                    // keep()'s copy
  bool frozen_ = false;
  uint32_t lastInstances_ = 0;  // the instance count the last update left
  uint32_t lastOverflow_ = 0;   // and the instances it could not draw (GpuLod::overflowWord)
};

}  // namespace

std::unique_ptr<PathDrawer> makeGpuIndirectDrawer(const PathEnv& env) {
  return std::make_unique<GpuIndirectDrawer>(env);
}

}  // namespace lb
