// The tessellation path: the base grid's patches (or the scheme's own patch mesh) through the
// scheme's control shader, in split draws that stay within the device's draw limits.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "render/draw_limits.h"
#include "render/patch_grid.h"
#include "render/path_drawer.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"
#include "vk/context.h"
#include "vk/resources.h"

namespace lb {

uint32_t maxVerticesPerPatch(float level, Partitioning partitioning) {
  // Fractional modes round the segment count up to the next even/odd integer.
  int seg = int(std::ceil(std::max(level, 1.0f)));
  if (partitioning != Partitioning::Integer) seg += 1;
  seg = std::min(seg, 64);
  return uint32_t(seg + 1) * uint32_t(seg + 1);  // the quad domain bounds the triangle domain too
}

namespace {

class PatchDrawer : public PathDrawer {
 public:
  explicit PatchDrawer(const PathEnv& env) : env_(env) {
    const Scheme& scheme = env.scheme;
    const ParamValues& params = env.params;
    const Heightfield& terrain = env.terrain;
    const int grid = env.settings.grid;
    Topology topo = scheme.info().topology;
    controlPoints_ = controlPointCount(topo);
    PatchGeometry g = drawnPatches(scheme, params, terrain, grid);
    patchCount_ = uint32_t(g.indices.size() / controlPoints_);
    if (patchCount_ == 0 || g.indices.size() % controlPoints_ != 0 || g.bounds.size() != patchCount_)
      throw std::logic_error("scheme '" + scheme.info().name + "' supplied inconsistent patch geometry");
    for (uint32_t i : g.indices)
      if (i >= g.vertices.size()) throw std::logic_error("scheme '" + scheme.info().name + "': index out of range");
    // Schemes without a buffer still get a valid binding.
    if (g.schemeBuffer.empty()) g.schemeBuffer.assign(4, 0.0f);
    Context& ctx = env.ctx;
    auto bytes = [](const auto& v) { return VkDeviceSize(v.size() * sizeof(v[0])); };
    const MemoryTag geometry{GpuResource::Geometry, env.memory};
    vertices_ =
        createBufferWithData(ctx, g.vertices.data(), bytes(g.vertices), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, geometry);
    indices_ =
        createBufferWithData(ctx, g.indices.data(), bytes(g.indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, geometry);
    bounds_ = createBufferWithData(ctx, g.bounds.data(), bytes(g.bounds), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, geometry);
    schemeBuf_ = createBufferWithData(ctx, g.schemeBuffer.data(), bytes(g.schemeBuffer),
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, {GpuResource::SchemeTables, env.memory});
    capture_ = createReadBackBuffer(ctx, VkDeviceSize(patchCount_) * LB_CAPTURE_STRIDE * sizeof(float),
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, {GpuResource::Capture, env.memory});
    std::memset(capture_.mapped, 0, size_t(capture_.size));
    uint32_t perPatch = maxVerticesPerPatch(scheme.maxLevel(params), scheme.partitioning(params));
    patchesPerDraw_ = std::max(1u, std::min(kMaxVerticesPerDraw / perPatch, kMaxIndicesPerDraw / controlPoints_));
  }

  GeometryStages stages() const override {
    const SchemeInfo& info = env_.scheme.info();
    GeometryStages s;
    s.vert = "terrain.vert.spv";
    s.tesc = info.tesc + ".tesc.spv";
    s.tese = info.tese + "_" + partitioningName(env_.scheme.partitioning(env_.params)) + ".tese.spv";
    s.controlPoints = controlPoints_;
    return s;
  }
  PathBuffers buffers() const override {
    PathBuffers b;
    b.bounds = &bounds_;
    b.capture = &capture_;
    b.schemeBuf = &schemeBuf_;
    return b;
  }

  // Split so no draw can exceed kMaxVerticesPerDraw tessellated vertices or kMaxIndicesPerDraw indices.
  void recordDraws(VkCommandBuffer cmd, int /*slot*/) override {
    bindGeometry(cmd);
    drawRange(cmd, 0, patchCount_);
  }

  // The first share s of each eighth of the patches again (the share spreads over the grid), split
  // like the draws, so GPU time grows by about s while the counters stay exact.
  void recordSlowdown(VkCommandBuffer cmd, int /*slot*/, double s) override {
    constexpr uint32_t kBlocks = 8;
    for (uint32_t b = 0; b < kBlocks; ++b) {
      uint32_t begin = patchCount_ * b / kBlocks, end = patchCount_ * (b + 1) / kBlocks;
      uint32_t last = begin + uint32_t(std::floor(end * s) - std::floor(begin * s));  // floor(s * patches) in all
      drawRange(cmd, begin, last);
    }
  }

  void collect(int /*slot*/, double /*prepareMs*/, FrameResult& r) const override {
    r.draws = (patchCount_ + patchesPerDraw_ - 1) / patchesPerDraw_;
  }
  uint32_t patchCount() const override { return patchCount_; }
  uint32_t patchesPerDraw() const override { return patchesPerDraw_; }

 private:
  void bindGeometry(VkCommandBuffer cmd) const {
    VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, vertices_.buffer.ptr(), &zero);
    vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
  }
  void drawRange(VkCommandBuffer cmd, uint32_t begin, uint32_t end) const {
    for (uint32_t first = begin; first < end; first += patchesPerDraw_) {
      uint32_t count = std::min(patchesPerDraw_, end - first);
      DrawPush push{first};
      vkCmdPushConstants(cmd, env_.bindings.pipelineLayout, layoutStages(env_.ctx), 0, sizeof push, &push);
      vkCmdDrawIndexed(cmd, count * controlPoints_, 1, first * controlPoints_, 0, 0);
    }
  }

  PathEnv env_;
  Buffer vertices_, indices_, bounds_, capture_, schemeBuf_;
  uint32_t patchCount_ = 0, controlPoints_ = 4, patchesPerDraw_ = 1;
};

}  // namespace

std::unique_ptr<PathDrawer> makePatchDrawer(const PathEnv& env) {
  return std::make_unique<PatchDrawer>(env);
}

}  // namespace lb
