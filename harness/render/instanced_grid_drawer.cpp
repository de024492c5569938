// The instanced-grid path (render/instanced.h): the scheme's CPU selection every frame, copied into
// the slot's region of a host-visible instance buffer, and one instanced indexed draw per footprint
// that has instances.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "render/instance_upload.h"
#include "render/path_drawer.h"
#include "shaders/shared.h"
#include "vk/resources.h"

namespace lb {
namespace {

class InstancedGridDrawer : public PathDrawer {
 public:
  explicit InstancedGridDrawer(const PathEnv& env) : env_(env), upload_(env) {
    const std::string& name = env.scheme.info().name;
    lod_ = env.scheme.instancedLod(env.terrain, env.params);
    if (!lod_) throw std::logic_error("scheme '" + name + "' is instanced but supplies no InstancedLod");
    std::vector<glm::vec2> vertices;
    std::vector<uint32_t> indices;
    for (const Footprint& f : lod_->footprints()) {
      if (f.indices.empty() || f.indices.size() % 3 != 0)
        throw std::logic_error("scheme '" + name + "': footprint '" + f.name + "' is no triangle list");
      for (uint32_t i : f.indices)
        if (i >= f.vertices.size())
          throw std::logic_error("scheme '" + name + "': footprint '" + f.name + "' index out of range");
      ranges_.push_back({uint32_t(indices.size()), uint32_t(f.indices.size()), int32_t(vertices.size())});
      vertices.insert(vertices.end(), f.vertices.begin(), f.vertices.end());
      indices.insert(indices.end(), f.indices.begin(), f.indices.end());
    }
    if (ranges_.empty()) throw std::logic_error("scheme '" + name + "' supplied no footprints");
    auto bytes = [](const auto& v) { return VkDeviceSize(v.size() * sizeof(v[0])); };
    const MemoryTag geometry{GpuResource::Geometry, env.memory};
    vertices_ =
        createBufferWithData(env.ctx, vertices.data(), bytes(vertices), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, geometry);
    indices_ =
        createBufferWithData(env.ctx, indices.data(), bytes(indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, geometry);
  }

  GeometryStages stages() const override {
    GeometryStages s;
    s.vert = env_.scheme.info().vert + ".vert.spv";
    s.meshCapture = true;
    s.storeStage = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
    return s;
  }
  PathBuffers buffers() const override {
    PathBuffers b;
    b.instances = upload_.buffer();
    return b;
  }

  uint64_t prepare(int slot, const FrameUniforms& u, bool measured) override {
    selection_.countersWanted = measured;
    lod_->select(u, selection_);
    if (selection_.instances.size() != ranges_.size())
      throw std::logic_error("scheme '" + env_.scheme.info().name + "' selected instances for " +
                             std::to_string(selection_.instances.size()) + " footprints, it has " +
                             std::to_string(ranges_.size()));
    // Each slot owns a region; draws reach it through firstInstance, which gl_InstanceIndex includes.
    upload_.upload(slot, selection_);
    uint64_t triangles = 0;
    for (size_t f = 0; f < ranges_.size(); ++f)
      triangles += uint64_t(selection_.instances[f].size()) * (ranges_[f].indexCount / 3);
    return triangles;
  }

  // The selection ran on the CPU before the frame (FrameResult::lodCpuMs): no GPU LOD work.
  bool lodApart() const override { return true; }

  void recordDraws(VkCommandBuffer cmd, int slot) override {
    VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, vertices_.buffer.ptr(), &zero);
    vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
    drawShare(cmd, slot, -1);
  }
  // The first share of every footprint's instances again.
  void recordSlowdown(VkCommandBuffer cmd, int slot, double share) override { drawShare(cmd, slot, share); }

  void collect(int slot, double prepareMs, FrameResult& r) const override {
    r.lodCpuMs = prepareMs;
    for (size_t f = 0; f < upload_.footprints(slot); ++f) {
      r.instances += upload_.count(slot, f);
      r.draws += upload_.count(slot, f) > 0 ? 1 : 0;
    }
  }
  const Selection* selection() const override { return &selection_; }

 private:
  // share < 0: every instance.
  void drawShare(VkCommandBuffer cmd, int slot, double share) const {
    for (size_t f = 0; f < ranges_.size(); ++f) {
      const uint32_t count = upload_.count(slot, f);
      const uint32_t n = share < 0 ? count : uint32_t(std::floor(count * share));
      if (n > 0)
        vkCmdDrawIndexed(cmd, ranges_[f].indexCount, n, ranges_[f].firstIndex, ranges_[f].vertexOffset,
                         upload_.first(slot, f));
    }
  }

  // Each footprint's range in the vertex and index buffers.
  struct FootprintRange {
    uint32_t firstIndex = 0, indexCount = 0;
    int32_t vertexOffset = 0;
  };
  PathEnv env_;
  std::unique_ptr<InstancedLod> lod_;
  std::vector<FootprintRange> ranges_;
  Selection selection_;
  Buffer vertices_, indices_;
  InstanceUpload upload_;  // the selection's records, a region per slot, written in prepare()
};

}  // namespace

std::unique_ptr<PathDrawer> makeInstancedGridDrawer(const PathEnv& env) {
  return std::make_unique<InstancedGridDrawer>(env);
}

}  // namespace lb
