// Renderer construction: targets, terrain grid, descriptors and pipelines.
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>

#include "error.h"
#include "render/compute_pass.h"
#include "render/patch_grid.h"
#include "render/pipeline.h"
#include "render/renderer.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"
#include "terrain/normal_map.h"
#include "terrain/terrain_cache.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace lb {

// RenderMode reaches terrain.frag as the specialization constant kMode (Renderer::pipeline), where
// it is compared with the LB_MODE_* values of shaders/shared.h: the two must stay one enumeration.
static_assert(int(RenderMode::Shaded) == LB_MODE_SHADED && int(RenderMode::Heatmap) == LB_MODE_HEATMAP &&
                  int(RenderMode::Wireframe) == LB_MODE_WIREFRAME && int(RenderMode::Error) == LB_MODE_ERROR &&
                  int(RenderMode::Histogram) == LB_MODE_HISTOGRAM && int(RenderMode::Depth) == LB_MODE_DEPTH &&
                  int(RenderMode::Frontend) == LB_MODE_FRONTEND,
              "RenderMode and LB_MODE_* (shaders/shared.h) differ");

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
  if (settings.grid < 1 || settings.grid > 1024)
    throw std::runtime_error("grid must be within 1..1024 patches per side");
  createTargets();
  createDescriptors();
  VkCommandBuffer cmds[kSlots];
  commandPool_ = createCommandPool(ctx_, cmds, kSlots);
  for (int i = 0; i < kSlots; ++i) {
    slots_[size_t(i)].cmd = cmds[i];
    slots_[size_t(i)].fence = createFence(ctx_);
  }
}

Renderer::~Renderer() {
  // Frames in flight use the objects the members release; a destructor must not throw, so this
  // waits without VK_CHECK (a lost device has nothing left running anyway).
  vkQueueWaitIdle(ctx_.queue);
}

void Renderer::createTargets() {
  auto w = uint32_t(settings_.width), h = uint32_t(settings_.height);
  color_ = createImage(ctx_, w, h, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                       VK_IMAGE_ASPECT_COLOR_BIT);
  depth_ =
      createImage(ctx_, w, h, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
  errorTarget_ =
      createImage(ctx_, w, h, kErrorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                  VK_IMAGE_ASPECT_COLOR_BIT);
  readback_ = createBuffer(ctx_, VkDeviceSize(w) * h * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  histogram_ = createBuffer(ctx_, LB_HIST_COUNTERS * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  height_ = createImage(ctx_, uint32_t(terrain_.width), uint32_t(terrain_.height), VK_FORMAT_R32_SFLOAT,
                        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
  uploadImage(ctx_, height_, terrain_.h.data(), terrain_.h.size() * sizeof(float));
  sampler_ = createSampler(ctx_, VK_FILTER_NEAREST);
  // Once per terrain; the format is argued in terrain/normal_map.h.
  const auto tNormals = std::chrono::steady_clock::now();
  const std::shared_ptr<const NormalMap> kept = sharedNormalMap(terrain_);
  const NormalMap& normals = *kept;
  setupCosts_.normalMapS = std::chrono::duration<double>(std::chrono::steady_clock::now() - tNormals).count();
  normalMap_ = createImage(ctx_, uint32_t(normals.width), uint32_t(normals.height), VK_FORMAT_R16G16_SFLOAT,
                           VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
  uploadImage(ctx_, normalMap_, normals.texels.data(), normals.texels.size() * sizeof(uint16_t));
  linearSampler_ = createSampler(ctx_, VK_FILTER_LINEAR);
  uniformStride_ = (sizeof(FrameUniforms) + ctx_.props.limits.minUniformBufferOffsetAlignment - 1) &
                   ~(ctx_.props.limits.minUniformBufferOffsetAlignment - 1);
  uniforms_ = createBuffer(ctx_, uniformStride_ * kSlots, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
}

void Renderer::createGrid() {
  for (Buffer* b : {&vertices_, &indices_, &bounds_, &capture_, &schemeBuf_, &instances_, &mesh_, &lodState_,
                    &lodSnapshot_, &lodArgs_, &lodArgsReadback_})
    *b = {};
  lod_.reset();
  footprintRanges_.clear();
  selection_ = {};
  instanceCapacity_ = meshCapacity_ = 0;
  gpuIndirect_ = false;
  gpuLod_ = {};
  lodPipelines_.clear();
  if (scheme_->info().path == DrawPath::InstancedGrid) {
    createFootprints();
    return;
  }
  if (scheme_->info().path == DrawPath::GpuIndirect) {
    createGpuLod();
    return;
  }
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
  vertices_ = createBufferWithData(ctx_, g.vertices.data(), bytes(g.vertices), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  indices_ = createBufferWithData(ctx_, g.indices.data(), bytes(g.indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  bounds_ = createBufferWithData(ctx_, g.bounds.data(), bytes(g.bounds), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  schemeBuf_ =
      createBufferWithData(ctx_, g.schemeBuffer.data(), bytes(g.schemeBuffer), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  capture_ = createBuffer(ctx_, VkDeviceSize(patchCount_) * LB_CAPTURE_STRIDE * sizeof(float),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  std::memset(capture_.mapped, 0, size_t(capture_.size));
  uint32_t perPatch = maxVerticesPerPatch(scheme_->maxLevel(params_), scheme_->partitioning(params_));
  patchesPerDraw_ = std::max(1u, std::min(kMaxVerticesPerDraw / perPatch, kMaxIndicesPerDraw / controlPoints_));
}

void Renderer::createFootprints() {
  const std::string& name = scheme_->info().name;
  lod_ = scheme_->instancedLod(terrain_, params_);
  if (!lod_) throw std::logic_error("scheme '" + name + "' is instanced but supplies no InstancedLod");
  std::vector<glm::vec2> vertices;
  std::vector<uint32_t> indices;
  for (const Footprint& f : lod_->footprints()) {
    if (f.indices.empty() || f.indices.size() % 3 != 0)
      throw std::logic_error("scheme '" + name + "': footprint '" + f.name + "' is no triangle list");
    for (uint32_t i : f.indices)
      if (i >= f.vertices.size())
        throw std::logic_error("scheme '" + name + "': footprint '" + f.name + "' index out of range");
    footprintRanges_.push_back({uint32_t(indices.size()), uint32_t(f.indices.size()), int32_t(vertices.size())});
    vertices.insert(vertices.end(), f.vertices.begin(), f.vertices.end());
    indices.insert(indices.end(), f.indices.begin(), f.indices.end());
  }
  if (footprintRanges_.empty()) throw std::logic_error("scheme '" + name + "' supplied no footprints");
  auto bytes = [](const auto& v) { return VkDeviceSize(v.size() * sizeof(v[0])); };
  vertices_ = createBufferWithData(ctx_, vertices.data(), bytes(vertices), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  indices_ = createBufferWithData(ctx_, indices.data(), bytes(indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  minimalPatchBuffers();
}

void Renderer::minimalPatchBuffers() {
  // No patches: the bindings the tessellation path reads stay valid and unused.
  const float zeros[8] = {};
  bounds_ = createBufferWithData(ctx_, zeros, sizeof zeros, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  schemeBuf_ = createBufferWithData(ctx_, zeros, sizeof zeros, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  capture_ = createBuffer(ctx_, sizeof zeros, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  std::memset(capture_.mapped, 0, size_t(capture_.size));
  patchCount_ = 0;
  patchesPerDraw_ = 1;
}

void Renderer::createDescriptors() {
  const VkShaderStageFlags all = VK_SHADER_STAGE_ALL_GRAPHICS | VK_SHADER_STAGE_COMPUTE_BIT;
  bindings_ =
      createBindings(ctx_,
                     {{LB_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, all},
                      {LB_BINDING_HEIGHT, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, all},
                      {LB_BINDING_SCHEME_TEX, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, all},
                      {LB_BINDING_PATCH_BOUNDS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                      {LB_BINDING_CAPTURE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                      {LB_BINDING_SCHEME_BUF, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                      {LB_BINDING_HISTOGRAM, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                      {LB_BINDING_NORMAL, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
                      {LB_BINDING_INSTANCES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                      {LB_BINDING_MESH, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                      {LB_BINDING_LOD_STATE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                      {LB_BINDING_LOD_ARGS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all}},
                     all, sizeof(DrawPush));
}

void Renderer::setScheme(const Scheme& scheme, const ParamValues& params) {
  finish();
  pipelines_.clear();
  scheme_ = &scheme;
  params_ = resolveParams(scheme.info(), params);
  scheme.validate(params_);
  createGrid();
  schemeTex_ = {};
  const auto tPreprocess = std::chrono::steady_clock::now();
  // TRANSFER_SRC: readSchemeTexture() lets tests compare it with a CPU reference.
  const VkImageUsageFlags texUsage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if (!scheme.info().compute.empty()) {
    TextureSize size = scheme.computeOutputSize(terrain_);
    if (size.width < 1 || size.height < 1)
      throw std::runtime_error("scheme '" + scheme.info().name + "' declares a compute pass but no output size");
    schemeTex_ = createImage(ctx_, uint32_t(size.width), uint32_t(size.height), VK_FORMAT_R32G32B32A32_SFLOAT,
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
      throw std::logic_error("scheme '" + scheme.info().name + "' supplied a texture of " +
                             std::to_string(tex.channels) + " channels");
    if (tex.rgba.size() != size_t(tex.width) * size_t(tex.height) * size_t(tex.channels))
      throw std::logic_error("scheme '" + scheme.info().name + "' supplied a texture of the wrong size");
    const VkFormat format = tex.channels == 1 ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT;
    schemeTex_ = createImage(ctx_, uint32_t(tex.width), uint32_t(tex.height), format,
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
    w.dstSet = bindings_.set;
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
  writeInstanceDescriptors();
}

void Renderer::writeInstanceDescriptors() {
  // These bindings exist on every path (one pipeline layout); minimal buffers until a scheme or a frame needs more.
  if (!instances_.buffer) {
    instanceCapacity_ = 0;
    instances_ = createBuffer(ctx_, sizeof(InstanceRecord), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  }
  if (!mesh_.buffer) {
    meshCapacity_ = 0;
    mesh_ = createBuffer(ctx_, 16 + 3 * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    std::memset(mesh_.mapped, 0, size_t(mesh_.size));
  }
  const uint32_t zeros[8] = {};
  for (Buffer* b : {&lodState_, &lodArgs_})
    if (!b->buffer) *b = createBufferWithData(ctx_, zeros, sizeof zeros, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  const VkDescriptorBufferInfo infos[4] = {{instances_.buffer, 0, VK_WHOLE_SIZE},
                                           {mesh_.buffer, 0, VK_WHOLE_SIZE},
                                           {lodState_.buffer, 0, VK_WHOLE_SIZE},
                                           {lodArgs_.buffer, 0, VK_WHOLE_SIZE}};
  const uint32_t targets[4] = {LB_BINDING_INSTANCES, LB_BINDING_MESH, LB_BINDING_LOD_STATE, LB_BINDING_LOD_ARGS};
  VkWriteDescriptorSet w[4];
  for (int i = 0; i < 4; ++i) {
    w[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w[i].dstSet = bindings_.set;
    w[i].dstBinding = targets[i];
    w[i].descriptorCount = 1;
    w[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(ctx_.device, 4, w, 0, nullptr);
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
  // Timing modes Depth and Frontend run no fragment shader at all.
  const bool colour = mode != RenderMode::Depth && mode != RenderMode::Frontend;
  const bool frontend = mode == RenderMode::Frontend;
  const bool wire = mode == RenderMode::Wireframe;
  struct FragSpec {
    int mode;
    VkBool32 heightNormals;
  } fragValues{int(mode), settings_.testHeightNormals};
  VkBool32 captureValue = capture;
  VkSpecializationMapEntry captureEntry{1, 0, sizeof(VkBool32)};
  // The instanced path's histogram pass also captures the drawn mesh (analytic cracks).
  const bool instanced = info.path != DrawPath::Tessellation;
  VkBool32 meshValue = instanced;
  VkSpecializationMapEntry meshEntry{2, 0, sizeof(VkBool32)};
  VkSpecializationInfo meshSpec{1, &meshEntry, sizeof(VkBool32), &meshValue};
  VkSpecializationMapEntry fragEntries[2] = {{0, offsetof(FragSpec, mode), sizeof(int)},
                                             {1, offsetof(FragSpec, heightNormals), sizeof(VkBool32)}};
  VkSpecializationInfo modeSpec{2, fragEntries, sizeof(FragSpec), &fragValues};
  VkSpecializationInfo captureSpec{1, &captureEntry, sizeof(VkBool32), &captureValue};

  TessPipelineDesc d;
  d.layout = bindings_.pipelineLayout;
  if (instanced && info.tesc.empty()) {
    d.stages = {{VK_SHADER_STAGE_VERTEX_BIT, info.vert + ".vert.spv"}};
    d.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  } else {
    // A GPU-indirect scheme with a control shader (cbt-ts) draws its instances as patches.
    d.stages = {{VK_SHADER_STAGE_VERTEX_BIT, instanced ? info.vert + ".vert.spv" : "terrain.vert.spv"},
                {VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT, info.tesc + ".tesc.spv", &captureSpec},
                {VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT,
                 info.tese + "_" + partitioningName(scheme_->partitioning(params_)) + ".tese.spv"}};
  }
  if (colour) d.stages.push_back({VK_SHADER_STAGE_FRAGMENT_BIT, "terrain.frag.spv", &modeSpec});
  if (histogram)
    d.stages.push_back({VK_SHADER_STAGE_GEOMETRY_BIT, "histogram.geom.spv", instanced ? &meshSpec : nullptr});
  d.controlPoints = controlPoints_;
  d.width = uint32_t(settings_.width);
  d.height = uint32_t(settings_.height);
  d.polygonMode = wire ? VK_POLYGON_MODE_LINE : VK_POLYGON_MODE_FILL;
  // Wireframe lines lie on the shaded surface drawn first (Renderer::record): pulled slightly
  // towards the camera so the surface under them does not hide them, while hills still do.
  d.depthBias = wire;
  d.depthBiasConstant = wire ? -4.0f : 0.0f;
  d.depthBiasSlope = wire ? -1.0f : 0.0f;
  // The histogram pass only counts triangles; the frontend timing mode stops after the tessellator.
  d.rasterizerDiscard = histogram || frontend;
  d.depthCompare = wire ? VK_COMPARE_OP_LESS_OR_EQUAL : VK_COMPARE_OP_LESS;
  if (wire) {  // semitransparent, darkened lines: the shaded terrain stays visible under them
    d.blend.blendEnable = VK_TRUE;
    d.blend.srcColorBlendFactor = VK_BLEND_FACTOR_CONSTANT_COLOR;
    d.blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_CONSTANT_ALPHA;
    d.blend.colorBlendOp = VK_BLEND_OP_ADD;
    d.blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
    d.blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    d.blend.alphaBlendOp = VK_BLEND_OP_ADD;
    // line = 0.5 x level colour + 0.4 x surface: darker than the surface, tinted by the level.
    d.blendConstants = {0.5f, 0.5f, 0.5f, 0.6f};
  }
  if (colour) d.colorFormat = mode == RenderMode::Error ? kErrorFormat : kColorFormat;
  d.depthFormat = frontend ? VK_FORMAT_UNDEFINED : kDepthFormat;
  return pipelines_[key] = createTessPipeline(ctx_, d);
}

}  // namespace lb
