// The mesh-shader path (VK_EXT_mesh_shader, docs/draw-paths.md "The mesh path"): the scheme's task
// shader reads one record per unit of the LOD its twin decides (a base-grid patch, a node of a CPU
// selection, a leaf of a GPU tree) and launches mesh workgroups that emit its triangles. The LOD
// comes from where the twin's path gets it (SchemeInfo::meshLod): the patches and their height
// bounds as the tessellation path draws them, the instanced path's CPU selection in the same
// instance records, or the GPU-indirect path's passes and state (that path's object, whose draw
// alone is replaced). Only devices with the extension and the taskShader and meshShader features
// build it; elsewhere the case is skipped with the reason.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "error.h"
#include "render/instance_upload.h"
#include "render/lod_state.h"
#include "render/patch_grid.h"
#include "render/path_drawer.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"
#include "vk/context.h"
#include "vk/resources.h"

namespace lb {
namespace {

uint32_t groupsFor(uint64_t records, uint64_t perGroup) {
  return uint32_t((records + perGroup - 1) / perGroup);
}

class MeshDrawer : public PathDrawer {
 public:
  explicit MeshDrawer(const PathEnv& env) : env_(env), upload_(env) {
    const SchemeInfo& info = env.scheme.info();
    Context& ctx = env.ctx;
    if (!ctx.meshShader)
      throw FeatureMissing("scheme '" + info.name +
                           "' draws with task and mesh shaders: the device lacks VK_EXT_mesh_shader (its taskShader "
                           "and meshShader features)");
    if (info.task.empty() || info.mesh.empty())
      throw std::logic_error("scheme '" + info.name + "' is a mesh scheme without a task or mesh shader");
    switch (info.meshLod) {
      case DrawPath::Tessellation:
        buildPatches();
        break;
      case DrawPath::InstancedGrid:
        lod_ = env.scheme.instancedLod(env.terrain, env.params);
        if (!lod_) throw std::logic_error("scheme '" + info.name + "' draws a CPU selection but supplies none");
        break;
      case DrawPath::GpuIndirect: {
        gpu_ = makeGpuIndirectDrawer(env);
        const GpuLod& g = gpu_->lodState()->gpuLod();
        if (g.meshTasksWord < 0 || g.meshTaskRecords == 0 || uint64_t(g.meshTasksWord + 3) > g.initialState.size())
          throw std::logic_error("scheme '" + info.name + "' names no mesh-task arguments in its LOD state");
        // The passes size the draw by the records they wrote: it must stay within the task grid.
        const uint32_t most = groupsFor(g.maxInstances, g.meshTaskRecords);
        if (most > ctx.meshLimits.maxTaskWorkGroupCountX || most > ctx.meshLimits.maxTaskWorkGroupTotalCount)
          throw FeatureMissing("scheme '" + info.name + "': " + std::to_string(g.maxInstances) + " records need " +
                               std::to_string(most) + " task workgroups, the device launches at most " +
                               std::to_string(std::min(ctx.meshLimits.maxTaskWorkGroupCountX,
                                                       ctx.meshLimits.maxTaskWorkGroupTotalCount)));
        break;
      }
      case DrawPath::Mesh:
        throw std::logic_error("scheme '" + info.name + "': a mesh path amplifies another path's LOD");
    }
    std::vector<uint32_t> table = env.scheme.meshTable();
    if (table.empty() && lod_) table = lod_->meshTable();
    if (!table.empty())
      table_ = createBufferWithData(ctx, table.data(), VkDeviceSize(table.size() * sizeof(uint32_t)),
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, {GpuResource::SchemeTables, env.memory});
  }

  GeometryStages stages() const override {
    const SchemeInfo& info = env_.scheme.info();
    GeometryStages s;
    s.task = info.task + ".task.spv";
    s.mesh = info.mesh + ".mesh.spv";
    s.meshCapture = true;
    s.storeStage = VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT | VK_PIPELINE_STAGE_2_MESH_SHADER_BIT_EXT;
    return s;
  }

  PathBuffers buffers() const override {
    PathBuffers b = gpu_ ? gpu_->buffers() : PathBuffers{};
    if (patchCount_ > 0) {
      b.bounds = &bounds_;
      b.capture = &capture_;
      b.instances = &patches_;
    } else if (lod_) {
      b.instances = upload_.buffer();
    }
    b.meshTable = table_.buffer ? &table_ : nullptr;
    return b;
  }

  uint64_t prepare(int slot, const FrameUniforms& u, bool measured) override {
    if (gpu_) return gpu_->prepare(slot, u, measured);
    if (!lod_) return 0;  // patches: the task shader decides; the frame core sizes the capture by what was drawn
    selection_.countersWanted = measured;
    lod_->select(u, selection_);
    if (selection_.instances.size() != lod_->footprints().size())
      throw std::logic_error("scheme '" + env_.scheme.info().name + "' selected instances for " +
                             std::to_string(selection_.instances.size()) + " footprints, it has " +
                             std::to_string(lod_->footprints().size()));
    upload_.upload(slot, selection_);
    uint64_t triangles = 0;
    for (size_t f = 0; f < selection_.instances.size(); ++f)
      triangles += uint64_t(selection_.instances[f].size()) * (lod_->footprints()[f].indices.size() / 3);
    return triangles;
  }

  // The instanced path's CPU selection or the GPU-indirect path's passes; the patches decide in the draw.
  bool lodApart() const override { return patchCount_ == 0; }
  void recordLod(VkCommandBuffer cmd, uint32_t dynOffset) override {
    if (!gpu_) return;
    gpu_->recordLod(cmd, dynOffset);
    // The passes' records, counts and task arguments, for the task and mesh shaders and the draw.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT |
                      VK_PIPELINE_STAGE_2_MESH_SHADER_BIT_EXT,
                  VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  }

  void recordDraws(VkCommandBuffer cmd, int slot) override { drawShare(cmd, slot, -1); }
  // The first share of the records again; nothing where the GPU decides the counts.
  void recordSlowdown(VkCommandBuffer cmd, int slot, double share) override {
    if (!gpu_) drawShare(cmd, slot, share);
  }
  void recordAfterDraws(VkCommandBuffer cmd, int slot) override {
    if (gpu_) gpu_->recordAfterDraws(cmd, slot);
  }

  void collect(int slot, double prepareMs, FrameResult& r) const override {
    if (gpu_) {
      gpu_->collect(slot, prepareMs, r);
    } else if (lod_) {
      r.lodCpuMs = prepareMs;
      r.instances = upload_.total(slot);
      r.draws = r.instances > 0 ? 1 : 0;
    } else {
      r.draws = 1;
    }
  }

  uint32_t patchCount() const override { return patchCount_; }
  uint32_t patchesPerDraw() const override { return std::max(patchCount_, 1u); }
  const Selection* selection() const override { return lod_ ? &selection_ : nullptr; }
  LodState* lodState() override { return gpu_ ? gpu_->lodState() : nullptr; }

 private:
  // The base grid's patches as the tessellation path draws them (render/patch_grid.h), one record
  // a patch: its four corners in the world, a = (c0, c1), b = (c2, c3), in the control points' order.
  void buildPatches() {
    const Scheme& scheme = env_.scheme;
    if (scheme.info().topology != Topology::Quad4)
      throw std::logic_error("scheme '" + scheme.info().name + "': the mesh path draws quad patches only");
    PatchGeometry g = drawnPatches(scheme, env_.params, env_.terrain, env_.settings.grid);
    patchCount_ = uint32_t(g.indices.size() / 4);
    if (patchCount_ == 0 || g.indices.size() % 4 != 0 || g.bounds.size() != patchCount_)
      throw std::logic_error("scheme '" + scheme.info().name + "' supplied inconsistent patch geometry");
    std::vector<InstanceRecord> records(patchCount_);
    for (uint32_t p = 0; p < patchCount_; ++p) {
      glm::vec2 c[4];
      for (int k = 0; k < 4; ++k) {
        const uint32_t i = g.indices[size_t(p) * 4 + size_t(k)];
        if (i >= g.vertices.size()) throw std::logic_error("scheme '" + scheme.info().name + "': index out of range");
        c[k] = g.vertices[i];
      }
      records[p] = {glm::vec4(c[0], c[1]), glm::vec4(c[2], c[3])};
    }
    Context& ctx = env_.ctx;
    auto bytes = [](const auto& v) { return VkDeviceSize(v.size() * sizeof(v[0])); };
    const MemoryTag geometry{GpuResource::Geometry, env_.memory};
    patches_ = createBufferWithData(ctx, records.data(), bytes(records), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, geometry);
    bounds_ = createBufferWithData(ctx, g.bounds.data(), bytes(g.bounds), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, geometry);
    capture_ = createReadBackBuffer(ctx, VkDeviceSize(patchCount_) * LB_CAPTURE_STRIDE * sizeof(float),
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, {GpuResource::Capture, env_.memory});
    std::memset(capture_.mapped, 0, size_t(capture_.size));
    if (groupsFor(patchCount_, LB_MESH_TASK_RECORDS) > ctx.meshLimits.maxTaskWorkGroupCountX)
      throw FeatureMissing("scheme '" + scheme.info().name + "': " + std::to_string(patchCount_) +
                           " patches need more task workgroups than the device launches in one draw");
  }

  // share < 0: every record.
  void drawShare(VkCommandBuffer cmd, int slot, double share) const {
    if (gpu_) {
      const GpuLod& g = gpu_->lodState()->gpuLod();
      const DrawPush push{0, 0};
      vkCmdPushConstants(cmd, env_.bindings.pipelineLayout, layoutStages(env_.ctx), 0, sizeof push, &push);
      env_.ctx.cmdDrawMeshTasksIndirect(cmd, gpu_->buffers().lodState->buffer,
                                        VkDeviceSize(g.meshTasksWord) * sizeof(uint32_t), 1,
                                        sizeof(VkDrawMeshTasksIndirectCommandEXT));
      return;
    }
    const uint32_t first = lod_ ? (upload_.footprints(slot) > 0 ? upload_.first(slot, 0) : 0) : 0;
    const uint32_t all = lod_ ? upload_.total(slot) : patchCount_;
    const uint32_t count = share < 0 ? all : uint32_t(std::floor(all * share));
    if (count == 0) return;
    const DrawPush push{first, count};
    vkCmdPushConstants(cmd, env_.bindings.pipelineLayout, layoutStages(env_.ctx), 0, sizeof push, &push);
    env_.ctx.cmdDrawMeshTasks(cmd, groupsFor(count, LB_MESH_TASK_RECORDS), 1, 1);
  }

  PathEnv env_;
  // Patches (SchemeInfo::meshLod Tessellation): their corners, height bounds and captured factors.
  uint32_t patchCount_ = 0;
  Buffer patches_, bounds_, capture_;
  // A CPU selection (InstancedGrid): the scheme's LOD and the records of each slot.
  std::unique_ptr<InstancedLod> lod_;
  Selection selection_;
  InstanceUpload upload_;
  // GPU passes (GpuIndirect): the GPU-indirect path's object, all but its draw.
  std::unique_ptr<PathDrawer> gpu_;
  Buffer table_;  // Scheme::meshTable
};

}  // namespace

std::unique_ptr<PathDrawer> makeMeshDrawer(const PathEnv& env) {
  return std::make_unique<MeshDrawer>(env);
}

}  // namespace lb
