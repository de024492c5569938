// Renderer construction: targets, descriptors, the scheme's draw path and pipelines by mode.
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>

#include "error.h"
#include "render/compute_pass.h"
#include "render/device_terrain.h"
#include "render/pipeline.h"
#include "render/renderer.h"
#include "render/sample_map_pages.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"
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
                       VK_IMAGE_ASPECT_COLOR_BIT, tag(GpuResource::Frame));
  depth_ = createImage(ctx_, w, h, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT,
                       tag(GpuResource::Frame));
  errorTarget_ =
      createImage(ctx_, w, h, kErrorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                  VK_IMAGE_ASPECT_COLOR_BIT, tag(GpuResource::Frame));
  readback_ =
      createBuffer(ctx_, VkDeviceSize(w) * h * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, tag(GpuResource::Capture));
  histogram_ = createBuffer(ctx_, LB_HIST_COUNTERS * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true,
                            tag(GpuResource::Capture));
  // The heights as pages behind their table (one page unless the terrain says "page") and the
  // normal map: a large terrain's copy is kept from the renderer before (render/device_terrain.h).
  DeviceTerrainOptions copyOptions;
  copyOptions.heightDefect = settings_.testPageDefect;
  copyOptions.heightLayers = settings_.testPageLayers;
  copyOptions.normalCells = settings_.testNormalPageCells;
  copyOptions.normalLayers = settings_.testNormalPageLayers;
  copyOptions.normalDefect = settings_.testNormalPageDefect ? NormalPageDefect::OriginOffByOne : NormalPageDefect::None;
  copyOptions.normalCoarseFrom = settings_.testNormalCoarseFrom;
  bool reused = false;
  terrainCopy_ = deviceTerrain(ctx_, terrain_, copyOptions, &reused);
  // A kept copy cost this renderer nothing: costs.terrains records each stage's largest.
  setupCosts_.pagesS = reused ? 0.0 : terrainCopy_->pagesS;
  setupCosts_.normalMapS = reused ? 0.0 : terrainCopy_->normalMapS;
  sampler_ = createSampler(ctx_, VK_FILTER_NEAREST);
  uniformStride_ = (sizeof(FrameUniforms) + ctx_.props.limits.minUniformBufferOffsetAlignment - 1) &
                   ~(ctx_.props.limits.minUniformBufferOffsetAlignment - 1);
  uniforms_ =
      createBuffer(ctx_, uniformStride_ * kSlots, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true, tag(GpuResource::Frame));
}

void Renderer::createDescriptors() {
  const VkShaderStageFlags all = layoutStages(ctx_);
  std::vector<DescriptorBinding> layout = heightBindings(all);
  for (const DescriptorBinding& b : normalBindings(VK_SHADER_STAGE_FRAGMENT_BIT)) layout.push_back(b);
  layout.push_back(sampleMapBinding(all));
  layout.insert(layout.end(), {{LB_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, all},
                               {LB_BINDING_SCHEME_TEX, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, all},
                               {LB_BINDING_PATCH_BOUNDS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                               {LB_BINDING_CAPTURE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                               {LB_BINDING_SCHEME_BUF, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                               {LB_BINDING_HISTOGRAM, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                               {LB_BINDING_INSTANCES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                               {LB_BINDING_MESH, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                               {LB_BINDING_LOD_STATE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                               {LB_BINDING_LOD_ARGS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all},
                               {LB_BINDING_MESH_TABLE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, all}});
  bindings_ = createBindings(ctx_, layout, all, sizeof(DrawPush));
}

void Renderer::setScheme(const Scheme& scheme, const ParamValues& params) {
  finish();
  pipelines_.clear();
  scheme_ = &scheme;
  params_ = resolveParams(scheme.info(), params);
  scheme.validate(params_);
  path_.reset();
  mesh_ = {};
  for (Buffer& b : placeholders_) b = {};
  meshCapacity_ = 0;
  meshAtLeast_ = 0;
  PathEnv env{ctx_, terrain_, settings_, scheme, params_, bindings_, kSlots};
  env.memory = &memory_;
  env.finish = [this] { finish(); };
  env.rebind = [this] { bindPathBuffers(); };
  env.uniforms = [this](const CameraPose& pose) {
    fillUniforms(nextSlot_, pose, pose);
    return UniformSlot{nextSlot_, uint32_t(uniformStride_ * VkDeviceSize(nextSlot_))};
  };
  meshStages_ = false;
  // Timed with the preprocessing: a path's per-terrain LOD state (an instanced scheme's trees and
  // tables, chunked's offline meshes) is built with the draw path object.
  const auto tPreprocess = std::chrono::steady_clock::now();
  path_ = makePathDrawer(env);
  meshStages_ = !path_->stages().mesh.empty();
  schemeTex_ = {};
  sampleMap_.clear();
  if (const SampleMap map = scheme.sampleMap(terrain_, params_))
    sampleMap_ = createSampleMapPages(ctx_, terrainCopy_->heights, map, tag(GpuResource::SchemeTables));
  // TRANSFER_SRC: readSchemeTexture() lets tests compare it with a CPU reference.
  const VkImageUsageFlags texUsage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if (!scheme.info().compute.empty()) {
    TextureSize size = scheme.computeOutputSize(terrain_);
    if (size.width < 1 || size.height < 1)
      throw std::runtime_error("scheme '" + scheme.info().name + "' declares a compute pass but no output size");
    schemeTex_ =
        createImage(ctx_, uint32_t(size.width), uint32_t(size.height), VK_FORMAT_R32G32B32A32_SFLOAT,
                    texUsage | VK_IMAGE_USAGE_STORAGE_BIT, VK_IMAGE_ASPECT_COLOR_BIT, tag(GpuResource::SchemeTables));
    FrameUniforms packed{};
    scheme.update(packed, params_);
    ComputePush push{};
    push.terrain = glm::vec4(terrain_.extent, float(settings_.grid), terrain_.minHeight, terrain_.maxHeight);
    std::memcpy(push.params, packed.params, sizeof push.params);
    runComputePass(ctx_, scheme.info().compute, sampler_, terrainCopy_->heights, schemeTex_, push);
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
    schemeTex_ =
        createImage(ctx_, uint32_t(tex.width), uint32_t(tex.height), format, texUsage | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                    VK_IMAGE_ASPECT_COLOR_BIT, tag(GpuResource::SchemeTables));
    uploadImage(ctx_, schemeTex_, tex.rgba.data(), tex.rgba.size() * sizeof(float));
    schemeTexChannels_ = tex.channels;
  }
  setupCosts_.preprocessS = std::chrono::duration<double>(std::chrono::steady_clock::now() - tPreprocess).count();

  VkDescriptorBufferInfo ub{uniforms_.buffer, 0, sizeof(FrameUniforms)};
  VkDescriptorImageInfo si{sampler_, schemeTex_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorBufferInfo hb{histogram_.buffer, 0, VK_WHOLE_SIZE};
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
      write(LB_BINDING_SCHEME_TEX, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, &si, nullptr),
      write(LB_BINDING_HISTOGRAM, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nullptr, &hb),
  };
  vkUpdateDescriptorSets(ctx_.device, uint32_t(std::size(writes)), writes, 0, nullptr);
  writeHeightDescriptors(ctx_, bindings_.set, terrainCopy_->heights, sampler_);
  writeNormalDescriptors(ctx_, bindings_.set, terrainCopy_->normals, sampler_);
  writeSampleMapDescriptors(ctx_, bindings_.set, sampleMap_, terrainCopy_->heights, sampler_);
  bindPathBuffers();
}

void Renderer::bindPathBuffers() {
  // A binding the path leaves empty gets a small placeholder; the capture's is read back
  // (capturedLevels), so it is host-visible and zeroed like the mesh capture's.
  const uint32_t zeros[8] = {};
  auto placeholder = [&](size_t k, const Buffer* own) -> const Buffer& {
    if (own) return *own;
    Buffer& b = placeholders_[k];
    if (b.buffer) return b;
    if (k == 1 || k == 3) {  // capture, instances: host-visible
      b = createBuffer(ctx_, sizeof zeros, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, tag(GpuResource::Frame));
      std::memset(b.mapped, 0, size_t(b.size));
    } else {
      b = createBufferWithData(ctx_, zeros, sizeof zeros, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, tag(GpuResource::Frame));
    }
    return b;
  };
  if (!mesh_.buffer) {
    meshCapacity_ = 0;
    mesh_ = createBuffer(ctx_, 16 + 3 * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, tag(GpuResource::Capture));
    std::memset(mesh_.mapped, 0, size_t(mesh_.size));
  }
  const PathBuffers own = path_->buffers();
  constexpr int kBuffers = 8;
  const Buffer* buffers[kBuffers] = {&placeholder(0, own.bounds),    &placeholder(1, own.capture),
                                     &placeholder(2, own.schemeBuf), &placeholder(3, own.instances),
                                     &placeholder(4, own.lodState),  &placeholder(5, own.lodArgs),
                                     &placeholder(6, own.meshTable), &mesh_};
  const uint32_t targets[kBuffers] = {LB_BINDING_PATCH_BOUNDS, LB_BINDING_CAPTURE,   LB_BINDING_SCHEME_BUF,
                                      LB_BINDING_INSTANCES,    LB_BINDING_LOD_STATE, LB_BINDING_LOD_ARGS,
                                      LB_BINDING_MESH_TABLE,   LB_BINDING_MESH};
  VkDescriptorBufferInfo infos[kBuffers];
  VkWriteDescriptorSet w[kBuffers];
  for (int i = 0; i < kBuffers; ++i) {
    infos[i] = {buffers[i]->buffer, 0, VK_WHOLE_SIZE};
    w[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w[i].dstSet = bindings_.set;
    w[i].dstBinding = targets[i];
    w[i].descriptorCount = 1;
    w[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(ctx_.device, kBuffers, w, 0, nullptr);
}

VkPipeline Renderer::pipeline(RenderMode mode, bool capture) {
  int key = int(mode) * 2 + (capture ? 1 : 0);
  if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second;
  const GeometryStages g = path_->stages();
  if (mode == RenderMode::Wireframe && !ctx_.enabledFeatures.fillModeNonSolid)
    throw FeatureMissing("device lacks fillModeNonSolid: wireframe images are unavailable");
  bool histogram = mode == RenderMode::Histogram;
  // A mesh stage bins its own triangles; the other paths bin them in a geometry shader.
  const bool meshStages = !g.mesh.empty();
  if (histogram && !meshStages && !ctx_.enabledFeatures.geometryShader)
    throw FeatureMissing("device lacks geometryShader: triangle-size histograms are unavailable");
  if (capture && !ctx_.enabledFeatures.vertexPipelineStoresAndAtomics)
    throw FeatureMissing("device lacks vertexPipelineStoresAndAtomics: tessellation factors cannot be captured");
  // Timing modes Depth and Frontend run no fragment shader at all.
  const bool colour = mode != RenderMode::Depth && mode != RenderMode::Frontend;
  const bool frontend = mode == RenderMode::Frontend;
  const bool wire = mode == RenderMode::Wireframe;
  struct FragSpec {
    int mode;
    VkBool32 heightNormals, mipZero, normalPaged;
  } fragValues{int(mode), settings_.testHeightNormals, settings_.testMipZeroShading, terrainCopy_->normals.paged};
  VkBool32 captureValue = capture;
  VkSpecializationMapEntry captureEntry{1, 0, sizeof(VkBool32)};
  // Paths with instances capture the drawn mesh in the histogram pass (analytic cracks).
  VkBool32 meshValue = g.meshCapture;
  VkSpecializationMapEntry meshEntry{2, 0, sizeof(VkBool32)};
  VkSpecializationInfo meshSpec{1, &meshEntry, sizeof(VkBool32), &meshValue};
  VkSpecializationMapEntry fragEntries[4] = {{0, offsetof(FragSpec, mode), sizeof(int)},
                                             {1, offsetof(FragSpec, heightNormals), sizeof(VkBool32)},
                                             {2, offsetof(FragSpec, mipZero), sizeof(VkBool32)},
                                             {3, offsetof(FragSpec, normalPaged), sizeof(VkBool32)}};
  VkSpecializationInfo modeSpec{4, fragEntries, sizeof(FragSpec), &fragValues};
  VkSpecializationInfo captureSpec{1, &captureEntry, sizeof(VkBool32), &captureValue};
  // A mesh stage's histogram pass: constant 3 bins, constant 2 captures the mesh (as the geometry shader's).
  struct MeshSpec {
    VkBool32 capture, histogram;
  } meshStageValues{histogram && g.meshCapture, histogram};
  VkSpecializationMapEntry meshStageEntries[2] = {{2, offsetof(MeshSpec, capture), sizeof(VkBool32)},
                                                  {3, offsetof(MeshSpec, histogram), sizeof(VkBool32)}};
  VkSpecializationInfo meshStageSpec{2, meshStageEntries, sizeof(MeshSpec), &meshStageValues};

  TessPipelineDesc d;
  d.layout = bindings_.pipelineLayout;
  if (meshStages) {
    if (!g.task.empty()) d.stages.push_back({VK_SHADER_STAGE_TASK_BIT_EXT, g.task, &captureSpec});
    d.stages.push_back({VK_SHADER_STAGE_MESH_BIT_EXT, g.mesh, &meshStageSpec});
  } else {
    d.stages = {{VK_SHADER_STAGE_VERTEX_BIT, g.vert}};
    if (g.tesc.empty()) {
      d.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    } else {
      d.stages.push_back({VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT, g.tesc, &captureSpec});
      d.stages.push_back({VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT, g.tese});
    }
  }
  if (colour) d.stages.push_back({VK_SHADER_STAGE_FRAGMENT_BIT, "terrain.frag.spv", &modeSpec});
  if (histogram && !meshStages)
    d.stages.push_back({VK_SHADER_STAGE_GEOMETRY_BIT, "histogram.geom.spv", g.meshCapture ? &meshSpec : nullptr});
  d.controlPoints = g.controlPoints;
  d.heightArrays = uint32_t(terrainCopy_->heights.arrays.size());
  d.normalArrays = uint32_t(terrainCopy_->normals.arrays.size());
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
