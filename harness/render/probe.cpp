// The minimal loop: its own pipeline, descriptor and two-slot frame ring.
#include "render/probe.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "metrics/stats.h"
#include "render/patch_grid.h"
#include "terrain/heightfield.h"
#include "vk/context.h"
#include "vk/resources.h"
#include "vk/vk_check.h"

namespace lb {

namespace {

struct ProbePush {
  glm::mat4 viewProj;
  glm::vec4 terrain;  // extent, level
};

constexpr int kSlots = 2;
constexpr VkFormat kColor = VK_FORMAT_R8G8B8A8_UNORM, kDepth = VK_FORMAT_D32_SFLOAT;

// Every Vulkan object of the probe, destroyed in one place (also when a step throws).
struct ProbeObjects {
  Context& ctx;
  Image color, depth, height;
  Buffer vertices, indices;
  VkSampler sampler = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkCommandBuffer cmd[kSlots] = {};
  VkFence fence[kSlots] = {};
  explicit ProbeObjects(Context& c) : ctx(c) {}
  ~ProbeObjects() {
    vkDeviceWaitIdle(ctx.device);
    for (int i = 0; i < kSlots; ++i) {
      if (fence[i]) vkDestroyFence(ctx.device, fence[i], nullptr);
      if (cmd[i]) vkFreeCommandBuffers(ctx.device, ctx.commandPool, 1, &cmd[i]);
    }
    vkDestroyPipeline(ctx.device, pipeline, nullptr);
    vkDestroyPipelineLayout(ctx.device, layout, nullptr);
    vkDestroyDescriptorPool(ctx.device, pool, nullptr);
    vkDestroyDescriptorSetLayout(ctx.device, setLayout, nullptr);
    vkDestroySampler(ctx.device, sampler, nullptr);
    destroyBuffer(ctx, vertices);
    destroyBuffer(ctx, indices);
    for (Image* i : {&color, &depth, &height}) destroyImage(ctx, *i);
  }
};

void createPipeline(ProbeObjects& o, const ProbeOptions& opt) {
  const bool colour = opt.mode == RenderMode::Shaded, frontend = opt.mode == RenderMode::Frontend;
  const std::string stem = opt.vertexHeight ? "probe_height" : "probe";
  VkShaderModule mods[4] = {loadShaderModule(o.ctx, stem + ".vert.spv"), loadShaderModule(o.ctx, stem + ".tesc.spv"),
                            loadShaderModule(o.ctx, stem + "_integer.tese.spv"),
                            colour ? loadShaderModule(o.ctx, "probe.frag.spv") : VK_NULL_HANDLE};
  VkShaderStageFlagBits bits[4] = {VK_SHADER_STAGE_VERTEX_BIT, VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT,
                                   VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT, VK_SHADER_STAGE_FRAGMENT_BIT};
  VkPipelineShaderStageCreateInfo stages[4] = {};
  uint32_t n = 0;
  for (int i = 0; i < 4; ++i) {
    if (!mods[i]) continue;
    stages[n] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    stages[n].stage = bits[i];
    stages[n].module = mods[i];
    stages[n].pName = "main";
    ++n;
  }
  VkVertexInputBindingDescription vb{0, sizeof(float) * 2, VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription va{0, 0, VK_FORMAT_R32G32_SFLOAT, 0};
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vi.vertexBindingDescriptionCount = 1;
  vi.pVertexBindingDescriptions = &vb;
  vi.vertexAttributeDescriptionCount = 1;
  vi.pVertexAttributeDescriptions = &va;
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_PATCH_LIST;
  VkPipelineTessellationStateCreateInfo ts{VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_STATE_CREATE_INFO};
  ts.patchControlPoints = 4;
  VkViewport viewport{0, 0, float(opt.width), float(opt.height), 0, 1};
  VkRect2D scissor{{0, 0}, {uint32_t(opt.width), uint32_t(opt.height)}};
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.pViewports = &viewport;
  vp.scissorCount = 1;
  vp.pScissors = &scissor;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = VK_CULL_MODE_NONE;  // as the renderer
  rs.lineWidth = 1.0f;
  rs.rasterizerDiscardEnable = frontend;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = VK_TRUE;
  ds.depthWriteEnable = VK_TRUE;
  ds.depthCompareOp = VK_COMPARE_OP_LESS;
  VkPipelineColorBlendAttachmentState att{};
  att.colorWriteMask = 0xf;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = colour ? 1 : 0;
  cb.pAttachments = colour ? &att : nullptr;
  VkFormat colorFormat = kColor;
  VkPipelineRenderingCreateInfo ri{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  ri.colorAttachmentCount = colour ? 1 : 0;
  ri.pColorAttachmentFormats = colour ? &colorFormat : nullptr;
  ri.depthAttachmentFormat = frontend ? VK_FORMAT_UNDEFINED : kDepth;
  VkGraphicsPipelineCreateInfo gi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &ri};
  gi.stageCount = n;
  gi.pStages = stages;
  gi.pVertexInputState = &vi;
  gi.pInputAssemblyState = &ia;
  gi.pTessellationState = &ts;
  gi.pViewportState = &vp;
  gi.pRasterizationState = &rs;
  gi.pMultisampleState = &ms;
  gi.pDepthStencilState = &ds;
  gi.pColorBlendState = &cb;
  gi.layout = o.layout;
  VkResult r = vkCreateGraphicsPipelines(o.ctx.device, VK_NULL_HANDLE, 1, &gi, nullptr, &o.pipeline);
  for (VkShaderModule m : mods)
    if (m) vkDestroyShaderModule(o.ctx.device, m, nullptr);
  VK_CHECK(r);
}

void createResources(ProbeObjects& o, const Heightfield& terrain, const ProbeOptions& opt) {
  Context& ctx = o.ctx;
  auto w = uint32_t(opt.width), h = uint32_t(opt.height);
  createImage(ctx, o.color, w, h, kColor, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
  createImage(ctx, o.depth, w, h, kDepth, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
  createImage(ctx, o.height, uint32_t(terrain.width), uint32_t(terrain.height), VK_FORMAT_R32_SFLOAT,
              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
  uploadImage(ctx, o.height, terrain.h.data(), terrain.h.size() * sizeof(float));
  auto verts = gridVertices(opt.grid, terrain.extent);
  auto idx = patchIndices(opt.grid, Topology::Quad4);
  createBufferWithData(ctx, o.vertices, verts.data(), verts.size() * sizeof(verts[0]), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  createBufferWithData(ctx, o.indices, idx.data(), idx.size() * sizeof(idx[0]), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = VK_FILTER_NEAREST;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VK_CHECK(vkCreateSampler(ctx.device, &si, nullptr, &o.sampler));
  VkDescriptorSetLayoutBinding b{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_ALL_GRAPHICS, nullptr};
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = 1;
  li.pBindings = &b;
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &li, nullptr, &o.setLayout));
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.maxSets = 1;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &size;
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &pi, nullptr, &o.pool));
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = o.pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &o.setLayout;
  VK_CHECK(vkAllocateDescriptorSets(ctx.device, &ai, &o.set));
  VkDescriptorImageInfo ii{o.sampler, o.height.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet wr{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  wr.dstSet = o.set;
  wr.dstBinding = 0;
  wr.descriptorCount = 1;
  wr.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  wr.pImageInfo = &ii;
  vkUpdateDescriptorSets(ctx.device, 1, &wr, 0, nullptr);
  VkPushConstantRange pc{VK_SHADER_STAGE_ALL_GRAPHICS, 0, sizeof(ProbePush)};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &o.setLayout;
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &pc;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &pli, nullptr, &o.layout));
  VkCommandBufferAllocateInfo ci{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ci.commandPool = ctx.commandPool;
  ci.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ci.commandBufferCount = 1;
  for (int i = 0; i < kSlots; ++i) {
    VK_CHECK(vkAllocateCommandBuffers(ctx.device, &ci, &o.cmd[i]));
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(ctx.device, &fi, nullptr, &o.fence[i]));
  }
}

}  // namespace

bool probeNeedsSplit(const Context& ctx) { return ctx.driverName.find("llvmpipe") != std::string::npos; }

ProbeResult runProbe(Context& ctx, const Heightfield& terrain, const CameraPose& pose, const ProbeOptions& opt) {
  if (opt.mode != RenderMode::Shaded && opt.mode != RenderMode::Depth && opt.mode != RenderMode::Frontend)
    throw std::invalid_argument("probe: mode must be shaded, depth or frontend");
  if (opt.frames < 1) throw std::invalid_argument("probe: need at least one timed frame");
  ProbeObjects o(ctx);
  createResources(o, terrain, opt);
  createPipeline(o, opt);
  GpuProfiler profiler(ctx, kSlots);
  CameraMatrices m = cameraMatrices(pose, float(opt.width) / float(opt.height), terrain.extent);
  ProbePush push{m.proj * m.view, glm::vec4(terrain.extent, opt.level, 0, 0)};
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
    VK_CHECK(vkWaitForFences(ctx.device, 1, &o.fence[s], VK_TRUE, UINT64_MAX));
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
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, o.layout, 0, 1, &o.set, 0, nullptr);
    vkCmdPushConstants(cmd, o.layout, VK_SHADER_STAGE_ALL_GRAPHICS, 0, sizeof push, &push);
    VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &o.vertices.buffer, &zero);
    vkCmdBindIndexBuffer(cmd, o.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    uint32_t draws = 0;
    for (uint32_t first = 0; first < patches; first += perDraw, ++draws)
      vkCmdDrawIndexed(cmd, std::min(perDraw, patches - first) * 4, 1, first * 4, 0, 0);
    result.draws = draws;
    profiler.endStats(cmd, s);
    vkCmdEndRendering(cmd);
    profiler.timestampBottom(cmd, s);
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkSubmitInfo sub{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    sub.commandBufferCount = 1;
    sub.pCommandBuffers = &cmd;
    VK_CHECK(vkResetFences(ctx.device, 1, &o.fence[s]));
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
