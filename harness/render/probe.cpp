// The minimal loop: its own descriptor and two-slot frame ring; its pipeline comes from the
// renderer's builder (render/pipeline.h) with the probe's shaders.
#include "render/probe.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "camera/camera_matrices.h"
#include "render/draw_limits.h"
#include "render/gpu_profiler.h"
#include "render/patch_grid.h"
#include "render/pipeline.h"
#include "render/scheme.h"
#include "stats.h"
#include "terrain/heightfield.h"
#include "vk/context.h"
#include "vk/resources.h"
#include "vk/vk_check.h"

namespace lb {

namespace {

constexpr int kSlots = 2;
constexpr VkFormat kColor = VK_FORMAT_R8G8B8A8_UNORM, kDepth = VK_FORMAT_D32_SFLOAT;

// Every Vulkan object of the probe, each owned by a vk::Unique: the members built so far are
// released when a later step throws, after the destructor has waited for the frames using them.
struct ProbeObjects {
  Context& ctx;
  GpuProfiler profiler;
  Image color, depth, height;
  Buffer vertices, indices;
  vk::Unique<VkSampler> sampler;
  Bindings bindings;
  vk::Unique<VkPipeline> pipeline;
  vk::Unique<VkCommandPool> commandPool;
  VkCommandBuffer cmd[kSlots] = {};  // released with commandPool
  vk::Unique<VkFence> fence[kSlots];
  explicit ProbeObjects(Context& c) : ctx(c), profiler(c, kSlots) {}
  ~ProbeObjects() { vkQueueWaitIdle(ctx.queue); }  // no VK_CHECK: a destructor must not throw
  ProbeObjects(const ProbeObjects&) = delete;
  ProbeObjects& operator=(const ProbeObjects&) = delete;
};

void createPipeline(ProbeObjects& o, const ProbeOptions& opt) {
  const bool colour = opt.mode == RenderMode::Shaded, frontend = opt.mode == RenderMode::Frontend;
  const std::string stem = opt.vertexHeight ? "probe_height" : "probe";
  TessPipelineDesc d;
  d.layout = o.bindings.pipelineLayout;
  if (opt.instanced) {
    d.stages = {{VK_SHADER_STAGE_VERTEX_BIT, "probe_instanced.vert.spv"}};
    d.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  } else {
    d.stages = {{VK_SHADER_STAGE_VERTEX_BIT, stem + ".vert.spv"},
                {VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT, stem + ".tesc.spv"},
                {VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT, stem + "_integer.tese.spv"}};
  }
  if (colour) d.stages.push_back({VK_SHADER_STAGE_FRAGMENT_BIT, "probe.frag.spv"});
  d.controlPoints = 4;
  d.width = uint32_t(opt.width);
  d.height = uint32_t(opt.height);
  d.rasterizerDiscard = frontend;
  if (colour) d.colorFormat = kColor;
  d.depthFormat = frontend ? VK_FORMAT_UNDEFINED : kDepth;
  o.pipeline = createTessPipeline(o.ctx, d);
}

void createResources(ProbeObjects& o, const Heightfield& terrain, const ProbeOptions& opt) {
  Context& ctx = o.ctx;
  auto w = uint32_t(opt.width), h = uint32_t(opt.height);
  o.color = createImage(ctx, w, h, kColor, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                        {GpuResource::Frame});
  o.depth = createImage(ctx, w, h, kDepth, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT,
                        {GpuResource::Frame});
  o.height = createImage(ctx, uint32_t(terrain.width), uint32_t(terrain.height), VK_FORMAT_R32_SFLOAT,
                         VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                         {GpuResource::Heights});
  uploadImage(ctx, o.height, terrain.h.data(), terrain.h.size() * sizeof(float));
  std::vector<glm::vec2> verts;
  std::vector<uint32_t> idx;
  if (opt.instanced) {
    // One patch pre-tessellated: (level+1)^2 lattice points, the tessellator's triangulation (the
    // cell diagonal flips between the patch's quadrants, as render/uniform_instanced.h draws it).
    const int l = int(opt.level);
    for (int z = 0; z <= l; ++z)
      for (int x = 0; x <= l; ++x) verts.emplace_back(float(x), float(z));
    for (int z = 0; z < l; ++z)
      for (int x = 0; x < l; ++x) {
        uint32_t a = uint32_t(z * (l + 1) + x), b = a + 1, c = a + uint32_t(l) + 2, e = a + uint32_t(l) + 1;
        if ((2 * x < l) == (2 * z < l))
          idx.insert(idx.end(), {a, b, c, a, c, e});
        else
          idx.insert(idx.end(), {a, b, e, b, c, e});
      }
  } else {
    verts = gridVertices(opt.grid, terrain.extent);
    idx = patchIndices(opt.grid, Topology::Quad4);
  }
  o.vertices = createBufferWithData(ctx, verts.data(), verts.size() * sizeof(verts[0]),
                                    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, {GpuResource::Geometry});
  o.indices = createBufferWithData(ctx, idx.data(), idx.size() * sizeof(idx[0]), VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                                   {GpuResource::Geometry});
  o.sampler = createSampler(ctx, VK_FILTER_NEAREST);
  o.bindings = createBindings(ctx, {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_ALL_GRAPHICS}},
                              VK_SHADER_STAGE_ALL_GRAPHICS, sizeof(ProbePush));
  VkDescriptorImageInfo ii{o.sampler, o.height.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet wr{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  wr.dstSet = o.bindings.set;
  wr.dstBinding = 0;
  wr.descriptorCount = 1;
  wr.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  wr.pImageInfo = &ii;
  vkUpdateDescriptorSets(ctx.device, 1, &wr, 0, nullptr);
  o.commandPool = createCommandPool(ctx, o.cmd, kSlots);
  for (auto& f : o.fence) f = createFence(ctx);
}

}  // namespace

// Indices of the instanced loop's footprint: two triangles a cell.
static size_t idx6(float level) {
  return size_t(level) * size_t(level) * 6;
}

bool probeNeedsSplit(const Context& ctx) {
  return ctx.driverName.find("llvmpipe") != std::string::npos;
}

ProbeResult runProbe(Context& ctx, const Heightfield& terrain, const CameraPose& pose, const ProbeOptions& opt) {
  if (opt.mode != RenderMode::Shaded && opt.mode != RenderMode::Depth && opt.mode != RenderMode::Frontend)
    throw std::invalid_argument("probe: mode must be shaded, depth or frontend");
  if (opt.frames < 1) throw std::invalid_argument("probe: need at least one timed frame");
  ProbeObjects o(ctx);
  createResources(o, terrain, opt);
  createPipeline(o, opt);
  GpuProfiler& profiler = o.profiler;
  CameraMatrices m = cameraMatrices(pose, float(opt.width) / float(opt.height), terrain.extent);
  ProbePush push{m.proj * m.view, glm::vec4(terrain.extent, opt.level, float(opt.grid), 0)};
  if (opt.instanced && opt.level != float(int(opt.level)))
    throw std::invalid_argument("probe: the instanced loop needs an integer level");
  const uint32_t patches = uint32_t(opt.grid) * uint32_t(opt.grid);
  uint32_t perDraw = patches;
  if (opt.split)
    perDraw = std::max(1u, std::min(kMaxVerticesPerDraw / maxVerticesPerPatch(opt.level, Partitioning::Integer),
                                    kMaxIndicesPerDraw / 4));
  const bool colour = opt.mode == RenderMode::Shaded, depth = opt.mode != RenderMode::Frontend;
  ProbeResult result;
  bool busy[kSlots] = {};
  auto collect = [&](int s, bool timed) {
    if (!busy[s]) return;
    VK_CHECK(vkWaitForFences(ctx.device, 1, o.fence[s].ptr(), VK_TRUE, UINT64_MAX));
    busy[s] = false;
    GpuSample g = profiler.read(s);
    result.stats = g.stats;
    if (timed) result.gpuMs.push_back(g.gpuMs);
  };
  bool timedSlot[kSlots] = {};
  for (int i = 0; i < opt.warmup + opt.frames; ++i) {
    int s = i % kSlots;
    collect(s, timedSlot[s]);
    VkCommandBuffer cmd = o.cmd[s];
    VK_CHECK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
    profiler.reset(cmd, s);
    if (colour)
      imageBarrier(cmd, o.color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                   VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                   VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    if (depth)
      imageBarrier(cmd, o.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                   VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                   VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                   VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
    VkRenderingAttachmentInfo ca{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    ca.imageView = o.color.view;
    ca.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    ca.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    ca.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    ca.clearValue.color = {{1.0f, 0.0f, 1.0f, 1.0f}};
    VkRenderingAttachmentInfo da{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    da.imageView = o.depth.view;
    da.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    da.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    da.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    da.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {uint32_t(opt.width), uint32_t(opt.height)}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = colour ? 1 : 0;
    ri.pColorAttachments = colour ? &ca : nullptr;
    ri.pDepthAttachment = depth ? &da : nullptr;
    profiler.timestampTop(cmd, s);  // same placement as the renderer's: clears are inside the timing
    vkCmdBeginRendering(cmd, &ri);
    profiler.beginStats(cmd, s);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, o.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, o.bindings.pipelineLayout, 0, 1, &o.bindings.set, 0,
                            nullptr);
    vkCmdPushConstants(cmd, o.bindings.pipelineLayout, VK_SHADER_STAGE_ALL_GRAPHICS, 0, sizeof push, &push);
    VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, o.vertices.buffer.ptr(), &zero);
    vkCmdBindIndexBuffer(cmd, o.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    uint32_t draws = 0;
    if (opt.instanced) {
      vkCmdDrawIndexed(cmd, uint32_t(idx6(opt.level)), patches, 0, 0, 0);
      draws = 1;
    } else {
      for (uint32_t first = 0; first < patches; first += perDraw, ++draws)
        vkCmdDrawIndexed(cmd, std::min(perDraw, patches - first) * 4, 1, first * 4, 0, 0);
    }
    result.draws = draws;
    profiler.endStats(cmd, s);
    vkCmdEndRendering(cmd);
    profiler.timestampBottom(cmd, s);
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkSubmitInfo sub{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    sub.commandBufferCount = 1;
    sub.pCommandBuffers = &cmd;
    VK_CHECK(vkResetFences(ctx.device, 1, o.fence[s].ptr()));
    VK_CHECK(vkQueueSubmit(ctx.queue, 1, &sub, o.fence[s]));
    busy[s] = true;
    timedSlot[s] = i >= opt.warmup;
  }
  for (int k = 0; k < kSlots; ++k) {
    int s = (opt.warmup + opt.frames + k) % kSlots;  // oldest first
    collect(s, timedSlot[s]);
  }
  result.medianMs = summarize(result.gpuMs).median;
  return result;
}

}  // namespace lb
