// Renderer construction: targets, terrain grid, descriptors and pipelines.
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>

#include "render/compute_pass.h"
#include "error.h"
#include "render/patch_grid.h"
#include "render/renderer.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"
#include "terrain/normal_map.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace lb {

static constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_UNORM;
static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
static constexpr VkFormat kErrorFormat = VK_FORMAT_R32_SFLOAT;

uint32_t maxVerticesPerPatch(float level, Partitioning partitioning) {
  // Fractional modes round the segment count up to the next even/odd integer.
  int seg = int(std::ceil(std::max(level, 1.0f)));
  if (partitioning != Partitioning::Integer) seg += 1;
  seg = std::min(seg, 64);
  return uint32_t(seg + 1) * uint32_t(seg + 1);  // the quad domain bounds the triangle domain too
}

Renderer::Renderer(Context& ctx, const Heightfield& terrain, const RenderSettings& settings)
    : ctx_(ctx), terrain_(terrain), settings_(settings), profiler_(ctx, kSlots) {
  if (settings.width < 16 || settings.height < 16 || settings.width > 8192 || settings.height > 8192)
    throw std::runtime_error("resolution must be within 16..8192 pixels per side");
  if (settings.grid < 1 || settings.grid > 1024) throw std::runtime_error("grid must be within 1..1024 patches per side");
  createTargets();
  createDescriptors();
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = ctx_.commandPool;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  for (auto& s : slots_) {
    VK_CHECK(vkAllocateCommandBuffers(ctx_.device, &ai, &s.cmd));
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(ctx_.device, &fi, nullptr, &s.fence));
  }
}

Renderer::~Renderer() {
  finish();
  destroyPipelines();
  for (auto& s : slots_) {
    vkDestroyFence(ctx_.device, s.fence, nullptr);
    vkFreeCommandBuffers(ctx_.device, ctx_.commandPool, 1, &s.cmd);
  }
  vkDestroyPipelineLayout(ctx_.device, pipelineLayout_, nullptr);
  vkDestroyDescriptorPool(ctx_.device, descPool_, nullptr);
  vkDestroyDescriptorSetLayout(ctx_.device, setLayout_, nullptr);
  vkDestroySampler(ctx_.device, sampler_, nullptr);
  vkDestroySampler(ctx_.device, linearSampler_, nullptr);
  for (Buffer* b : {&histogram_, &readback_, &vertices_, &indices_, &bounds_, &capture_, &schemeBuf_, &uniforms_})
    destroyBuffer(ctx_, *b);
  for (Image* i : {&color_, &errorTarget_, &depth_, &height_, &schemeTex_, &normalMap_}) destroyImage(ctx_, *i);
}

void Renderer::createTargets() {
  auto w = uint32_t(settings_.width), h = uint32_t(settings_.height);
  createImage(ctx_, color_, w, h, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
              VK_IMAGE_ASPECT_COLOR_BIT);
  createImage(ctx_, depth_, w, h, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
  createImage(ctx_, errorTarget_, w, h, kErrorFormat,
              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
  createBuffer(ctx_, readback_, VkDeviceSize(w) * h * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  createBuffer(ctx_, histogram_, LB_HIST_COUNTERS * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  createImage(ctx_, height_, uint32_t(terrain_.width), uint32_t(terrain_.height), VK_FORMAT_R32_SFLOAT,
              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
  uploadImage(ctx_, height_, terrain_.h.data(), terrain_.h.size() * sizeof(float));
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = VK_FILTER_NEAREST;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VK_CHECK(vkCreateSampler(ctx_.device, &si, nullptr, &sampler_));
  // Once per terrain; the format is argued in terrain/normal_map.h.
  const auto tNormals = std::chrono::steady_clock::now();
  NormalMap normals = computeNormalMap(terrain_);
  setupCosts_.normalMapS = std::chrono::duration<double>(std::chrono::steady_clock::now() - tNormals).count();
  createImage(ctx_, normalMap_, uint32_t(normals.width), uint32_t(normals.height), VK_FORMAT_R16G16_SFLOAT,
              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
  uploadImage(ctx_, normalMap_, normals.texels.data(), normals.texels.size() * sizeof(uint16_t));
  si.magFilter = si.minFilter = VK_FILTER_LINEAR;
  VK_CHECK(vkCreateSampler(ctx_.device, &si, nullptr, &linearSampler_));
  uniformStride_ = (sizeof(FrameUniforms) + ctx_.props.limits.minUniformBufferOffsetAlignment - 1) &
                   ~(ctx_.props.limits.minUniformBufferOffsetAlignment - 1);
  createBuffer(ctx_, uniforms_, uniformStride_ * kSlots, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
}

void Renderer::createGrid() {
  for (Buffer* b : {&vertices_, &indices_, &bounds_, &capture_, &schemeBuf_}) destroyBuffer(ctx_, *b);
  Topology topo = scheme_->info().topology;
  controlPoints_ = controlPointCount(topo);
  PatchGeometry g = scheme_->patchGeometry(terrain_, params_, settings_.grid);
  if (g.vertices.empty()) {
    g.vertices = gridVertices(settings_.grid, terrain_.extent);
    g.indices = patchIndices(settings_.grid, topo);
    g.bounds = patchHeightBounds(terrain_, settings_.grid, topo);
  }
  // Schemes lay patches out terrain-locally; the terrain's origin moves them into the world, in
  // double and then rounded to float, as an engine without camera-relative coordinates would.
  if ((terrain_.originX != 0.0 || terrain_.originZ != 0.0) && !g.schemeUnits)
    for (glm::vec2& v : g.vertices)
      v = glm::vec2(float(double(v.x) + terrain_.originX), float(double(v.y) + terrain_.originZ));
  patchCount_ = uint32_t(g.indices.size() / controlPoints_);
  if (patchCount_ == 0 || g.indices.size() % controlPoints_ != 0 || g.bounds.size() != patchCount_)
    throw std::logic_error("scheme '" + scheme_->info().name + "' supplied inconsistent patch geometry");
  for (uint32_t i : g.indices)
    if (i >= g.vertices.size()) throw std::logic_error("scheme '" + scheme_->info().name + "': index out of range");
  // Schemes without a buffer still get a valid binding.
  if (g.schemeBuffer.empty()) g.schemeBuffer.assign(4, 0.0f);
  auto bytes = [](const auto& v) { return VkDeviceSize(v.size() * sizeof(v[0])); };
  createBufferWithData(ctx_, vertices_, g.vertices.data(), bytes(g.vertices), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  createBufferWithData(ctx_, indices_, g.indices.data(), bytes(g.indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  createBufferWithData(ctx_, bounds_, g.bounds.data(), bytes(g.bounds), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  createBufferWithData(ctx_, schemeBuf_, g.schemeBuffer.data(), bytes(g.schemeBuffer),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  createBuffer(ctx_, capture_, VkDeviceSize(patchCount_) * LB_CAPTURE_STRIDE * sizeof(float),
               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  std::memset(capture_.mapped, 0, size_t(capture_.size));
  uint32_t perPatch = maxVerticesPerPatch(scheme_->maxLevel(params_), scheme_->partitioning(params_));
  patchesPerDraw_ = std::max(1u, std::min(kMaxVerticesPerDraw / perPatch, kMaxIndicesPerDraw / controlPoints_));
}

void Renderer::createDescriptors() {
  VkShaderStageFlags all = VK_SHADER_STAGE_ALL_GRAPHICS | VK_SHADER_STAGE_COMPUTE_BIT;
  VkDescriptorSetLayoutBinding b[] = {
      {LB_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1, all, nullptr},
      {LB_BINDING_HEIGHT, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, all, nullptr},
      {LB_BINDING_SCHEME_TEX, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, all, nullptr},
      {LB_BINDING_PATCH_BOUNDS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {LB_BINDING_CAPTURE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {LB_BINDING_SCHEME_BUF, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {LB_BINDING_HISTOGRAM, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {LB_BINDING_NORMAL, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
  };
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = uint32_t(std::size(b));
  li.pBindings = b;
  VK_CHECK(vkCreateDescriptorSetLayout(ctx_.device, &li, nullptr, &setLayout_));
  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1},
                                  {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 3},
                                  {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4}};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.maxSets = 1;
  pi.poolSizeCount = uint32_t(std::size(sizes));
  pi.pPoolSizes = sizes;
  VK_CHECK(vkCreateDescriptorPool(ctx_.device, &pi, nullptr, &descPool_));
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = descPool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &setLayout_;
  VK_CHECK(vkAllocateDescriptorSets(ctx_.device, &ai, &set_));
  VkPushConstantRange pc{all, 0, sizeof(DrawPush)};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &setLayout_;
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &pc;
  VK_CHECK(vkCreatePipelineLayout(ctx_.device, &pli, nullptr, &pipelineLayout_));
}

void Renderer::setScheme(const Scheme& scheme, const ParamValues& params) {
  finish();
  destroyPipelines();
  scheme_ = &scheme;
  params_ = resolveParams(scheme.info(), params);
  scheme.validate(params_);
  createGrid();
  destroyImage(ctx_, schemeTex_);
  const auto tPreprocess = std::chrono::steady_clock::now();
  // TRANSFER_SRC: readSchemeTexture() lets tests compare it with a CPU reference.
  const VkImageUsageFlags texUsage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if (!scheme.info().compute.empty()) {
    TextureSize size = scheme.computeOutputSize(terrain_);
    if (size.width < 1 || size.height < 1)
      throw std::runtime_error("scheme '" + scheme.info().name + "' declares a compute pass but no output size");
    createImage(ctx_, schemeTex_, uint32_t(size.width), uint32_t(size.height), VK_FORMAT_R32G32B32A32_SFLOAT,
                texUsage | VK_IMAGE_USAGE_STORAGE_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    FrameUniforms packed{};
    scheme.update(packed, params_);
    ComputePush push{};
    push.terrain = glm::vec4(terrain_.extent, float(settings_.grid), terrain_.minHeight, terrain_.maxHeight);
    std::memcpy(push.params, packed.params, sizeof push.params);
    runComputePass(ctx_, scheme.info().compute, sampler_, height_.view, schemeTex_, push);
    schemeTexChannels_ = 4;
  } else {
    SchemeTexture tex = scheme.preprocessGrid(terrain_, params_, settings_.grid);
    if (tex.width == 0) tex = {1, 1, {0, 0, 0, 0}};
    if (tex.channels != 1 && tex.channels != 4)
      throw std::logic_error("scheme '" + scheme.info().name + "' supplied a texture of " + std::to_string(tex.channels) + " channels");
    if (tex.rgba.size() != size_t(tex.width) * size_t(tex.height) * size_t(tex.channels))
      throw std::logic_error("scheme '" + scheme.info().name + "' supplied a texture of the wrong size");
    const VkFormat format = tex.channels == 1 ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT;
    createImage(ctx_, schemeTex_, uint32_t(tex.width), uint32_t(tex.height), format,
                texUsage | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    uploadImage(ctx_, schemeTex_, tex.rgba.data(), tex.rgba.size() * sizeof(float));
    schemeTexChannels_ = tex.channels;
  }
  setupCosts_.preprocessS = std::chrono::duration<double>(std::chrono::steady_clock::now() - tPreprocess).count();

  VkDescriptorBufferInfo ub{uniforms_.buffer, 0, sizeof(FrameUniforms)};
  VkDescriptorImageInfo hi{sampler_, height_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorImageInfo si{sampler_, schemeTex_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorImageInfo ni{linearSampler_, normalMap_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorBufferInfo bb{bounds_.buffer, 0, VK_WHOLE_SIZE}, cb{capture_.buffer, 0, VK_WHOLE_SIZE},
      sb{schemeBuf_.buffer, 0, VK_WHOLE_SIZE}, hb{histogram_.buffer, 0, VK_WHOLE_SIZE};
  auto write = [&](uint32_t binding, VkDescriptorType type, const VkDescriptorImageInfo* img,
                   const VkDescriptorBufferInfo* buf) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set_;
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = type;
    w.pImageInfo = img;
    w.pBufferInfo = buf;
    return w;
  };
  VkWriteDescriptorSet writes[] = {
      write(LB_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, nullptr, &ub),
      write(LB_BINDING_HEIGHT, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, &hi, nullptr),
      write(LB_BINDING_SCHEME_TEX, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, &si, nullptr),
      write(LB_BINDING_PATCH_BOUNDS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nullptr, &bb),
      write(LB_BINDING_CAPTURE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nullptr, &cb),
      write(LB_BINDING_SCHEME_BUF, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nullptr, &sb),
      write(LB_BINDING_HISTOGRAM, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nullptr, &hb),
      write(LB_BINDING_NORMAL, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, &ni, nullptr),
  };
  vkUpdateDescriptorSets(ctx_.device, uint32_t(std::size(writes)), writes, 0, nullptr);
}

void Renderer::destroyPipelines() {
  for (auto& [key, p] : pipelines_) vkDestroyPipeline(ctx_.device, p, nullptr);
  pipelines_.clear();
}

VkPipeline Renderer::pipeline(RenderMode mode, bool capture) {
  int key = int(mode) * 2 + (capture ? 1 : 0);
  if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second;
  const SchemeInfo& info = scheme_->info();
  if (mode == RenderMode::Wireframe && !ctx_.enabledFeatures.fillModeNonSolid)
    throw FeatureMissing("device lacks fillModeNonSolid: wireframe images are unavailable");
  bool histogram = mode == RenderMode::Histogram;
  if (histogram && !ctx_.enabledFeatures.geometryShader)
    throw FeatureMissing("device lacks geometryShader: triangle-size histograms are unavailable");
  if (capture && !ctx_.enabledFeatures.vertexPipelineStoresAndAtomics)
    throw FeatureMissing("device lacks vertexPipelineStoresAndAtomics: tessellation factors cannot be captured");
  // Modules are destroyed on every exit, also when a later load or the pipeline creation throws.
  VkShaderModule mods[5] = {};
  struct ModuleGuard {
    VkDevice device;
    VkShaderModule* mods;
    ~ModuleGuard() {
      for (int i = 0; i < 5; ++i)
        if (mods[i]) vkDestroyShaderModule(device, mods[i], nullptr);
    }
  } guard{ctx_.device, mods};
  mods[0] = loadShaderModule(ctx_, "terrain.vert.spv");
  mods[1] = loadShaderModule(ctx_, info.tesc + ".tesc.spv");
  mods[2] = loadShaderModule(ctx_, info.tese + "_" + partitioningName(scheme_->partitioning(params_)) + ".tese.spv");
  // Timing modes Depth and Frontend run no fragment shader at all.
  const bool colour = mode != RenderMode::Depth && mode != RenderMode::Frontend;
  const bool frontend = mode == RenderMode::Frontend;
  if (colour) mods[3] = loadShaderModule(ctx_, "terrain.frag.spv");
  struct FragSpec {
    int mode;
    VkBool32 heightNormals;
  } fragValues{int(mode), settings_.testHeightNormals};
  VkBool32 captureValue = capture;
  VkSpecializationMapEntry captureEntry{1, 0, sizeof(VkBool32)};
  VkSpecializationMapEntry fragEntries[2] = {{0, offsetof(FragSpec, mode), sizeof(int)},
                                             {1, offsetof(FragSpec, heightNormals), sizeof(VkBool32)}};
  VkSpecializationInfo modeSpec{2, fragEntries, sizeof(FragSpec), &fragValues};
  VkSpecializationInfo captureSpec{1, &captureEntry, sizeof(VkBool32), &captureValue};
  if (histogram) mods[4] = loadShaderModule(ctx_, "histogram.geom.spv");
  VkPipelineShaderStageCreateInfo stages[5] = {};
  VkShaderStageFlagBits bits[5] = {VK_SHADER_STAGE_VERTEX_BIT, VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT,
                                   VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT, VK_SHADER_STAGE_FRAGMENT_BIT,
                                   VK_SHADER_STAGE_GEOMETRY_BIT};
  const VkSpecializationInfo* specs[5] = {nullptr, &captureSpec, nullptr, &modeSpec, nullptr};
  uint32_t stageCount = 0;
  for (uint32_t i = 0; i < 5; ++i) {
    if (!mods[i]) continue;
    VkPipelineShaderStageCreateInfo& st = stages[stageCount++];
    st = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    st.stage = bits[i];
    st.module = mods[i];
    st.pName = "main";
    st.pSpecializationInfo = specs[i];
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
  ts.patchControlPoints = controlPoints_;
  VkViewport viewport{0, 0, float(settings_.width), float(settings_.height), 0, 1};
  VkRect2D scissor{{0, 0}, {uint32_t(settings_.width), uint32_t(settings_.height)}};
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.pViewports = &viewport;
  vp.scissorCount = 1;
  vp.pScissors = &scissor;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = mode == RenderMode::Wireframe ? VK_POLYGON_MODE_LINE : VK_POLYGON_MODE_FILL;
  rs.cullMode = VK_CULL_MODE_NONE;  // back faces are counted by the histogram pass, not hidden
  rs.lineWidth = 1.0f;
  // Wireframe lines lie on the shaded surface drawn first (Renderer::record): pulled slightly
  // towards the camera so the surface under them does not hide them, while hills still do.
  const bool wire = mode == RenderMode::Wireframe;
  rs.depthBiasEnable = wire;
  rs.depthBiasConstantFactor = wire ? -4.0f : 0.0f;
  rs.depthBiasSlopeFactor = wire ? -1.0f : 0.0f;
  // The histogram pass only counts triangles; the frontend timing mode stops after the tessellator.
  rs.rasterizerDiscardEnable = histogram || frontend;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = VK_TRUE;
  ds.depthWriteEnable = VK_TRUE;
  ds.depthCompareOp = mode == RenderMode::Wireframe ? VK_COMPARE_OP_LESS_OR_EQUAL : VK_COMPARE_OP_LESS;
  VkPipelineColorBlendAttachmentState att{};
  att.colorWriteMask = 0xf;
  if (wire) {  // semitransparent, darkened lines: the shaded terrain stays visible under them
    att.blendEnable = VK_TRUE;
    att.srcColorBlendFactor = VK_BLEND_FACTOR_CONSTANT_COLOR;
    att.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_CONSTANT_ALPHA;
    att.colorBlendOp = VK_BLEND_OP_ADD;
    att.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
    att.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    att.alphaBlendOp = VK_BLEND_OP_ADD;
  }
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  // line = 0.5 x level colour + 0.4 x surface: darker than the surface, tinted by the level.
  if (wire) cb.blendConstants[0] = cb.blendConstants[1] = cb.blendConstants[2] = 0.5f, cb.blendConstants[3] = 0.6f;
  cb.attachmentCount = colour ? 1 : 0;
  cb.pAttachments = colour ? &att : nullptr;
  VkFormat colorFormat = mode == RenderMode::Error ? kErrorFormat : kColorFormat;
  VkPipelineRenderingCreateInfo ri{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  ri.colorAttachmentCount = colour ? 1 : 0;
  ri.pColorAttachmentFormats = colour ? &colorFormat : nullptr;
  ri.depthAttachmentFormat = frontend ? VK_FORMAT_UNDEFINED : kDepthFormat;
  VkGraphicsPipelineCreateInfo gi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &ri};
  gi.stageCount = stageCount;
  gi.pStages = stages;
  gi.pVertexInputState = &vi;
  gi.pInputAssemblyState = &ia;
  gi.pTessellationState = &ts;
  gi.pViewportState = &vp;
  gi.pRasterizationState = &rs;
  gi.pMultisampleState = &ms;
  gi.pDepthStencilState = &ds;
  gi.pColorBlendState = &cb;
  gi.layout = pipelineLayout_;
  VkPipeline p;
  VkResult r = vkCreateGraphicsPipelines(ctx_.device, VK_NULL_HANDLE, 1, &gi, nullptr, &p);
  VK_CHECK(r);
  pipelines_[key] = p;
  return p;
}

}  // namespace lb
