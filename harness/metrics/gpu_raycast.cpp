#include "metrics/gpu_raycast.h"

#include <cstring>
#include <string>

#include "camera/camera_matrices.h"
#include "error.h"
#include "metrics/raycast.h"
#include "metrics/raycast_shade.h"
#include "render/gpu_profiler.h"
#include "render/pipeline.h"
#include "shaders/footprint.h"
#include "shaders/raycast_params.h"
#include "terrain/heightfield.h"
#include "terrain/normal_map.h"
#include "terrain/page_layout.h"
#include "terrain/terrain_cache.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace lb {

namespace {

// The uniform block of shaders/raycast.glsl (std140): T is double or float as the shader's `real`.
// Members in declaration order at the offsets std140 gives them (matrix and vectors of T first).
template <typename T>
struct Params {
  T invViewProj[16];  // column-major
  T eye[4];
  T cell[4];  // x: cell width, z: cell depth
  float light[4];
  float slopeBlend[4];
  float rays[6][4];  // the float shader's ray: origin and direction, affine in the pixel's NDC
  int32_t size[4];
  int32_t grid[4];
  uint32_t levels[LB_RAYCAST_MAX_LEVELS][4];
  float shading[4];                                 // x: shadingPixelAngle; y: normal map levels
  uint32_t normalLevels[LB_RAYCAST_MAX_LEVELS][4];  // per normal map level: offset (texels), width, height
  int32_t pageGrid[4];                              // cells a page holds along x and z; pages along x
};
static_assert(sizeof(Params<double>) == 384 + 2 * LB_RAYCAST_MAX_LEVELS * 16);
static_assert(sizeof(Params<float>) == 288 + 2 * LB_RAYCAST_MAX_LEVELS * 16);

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

template <typename T>
void fillParams(void* out, const glm::dmat4& inv, const glm::dvec3& eye, double cw, double ch, int width, int height,
                const int grid[4], int samplesX, int samplesZ, float extent, const std::vector<uint32_t>& levels,
                float pixelAngle, const std::vector<uint32_t>& normalLevels, const PageLayout& pages) {
  Params<T> p{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) p.invViewProj[c * 4 + r] = T(inv[c][r]);
  for (int k = 0; k < 3; ++k) p.eye[k] = T(eye[k]);
  p.cell[0] = T(cw);
  p.cell[2] = T(ch);
  const glm::vec3 light = shadeLight();
  p.light[0] = light.x, p.light[1] = light.y, p.light[2] = light.z, p.light[3] = extent;
  p.slopeBlend[0] = kSlopeBlendLow, p.slopeBlend[1] = kSlopeBlendHigh;
  // pixelRay's near and far points are affine in NDC (x, y): their values at (0, 0) and slopes.
  auto unproject = [&](double x, double y, double z) {
    const glm::dvec4 a = inv * glm::dvec4(x, y, z, 1);
    return glm::dvec3(a) / a.w;
  };
  auto dir = [&](double x, double y) { return unproject(x, y, 1) - unproject(x, y, 0); };
  const glm::dvec3 rays[6] = {unproject(0, 0, 0),
                              unproject(1, 0, 0) - unproject(0, 0, 0),
                              unproject(0, 1, 0) - unproject(0, 0, 0),
                              dir(0, 0),
                              dir(1, 0) - dir(0, 0),
                              dir(0, 1) - dir(0, 0)};
  for (int k = 0; k < 6; ++k)
    for (int c = 0; c < 3; ++c) p.rays[k][c] = float(rays[k][c]);
  p.size[0] = width, p.size[1] = height, p.size[2] = samplesX, p.size[3] = samplesZ;
  std::memcpy(p.grid, grid, sizeof p.grid);
  std::memcpy(p.levels, levels.data(), levels.size() * sizeof(uint32_t));
  p.shading[0] = pixelAngle;
  p.shading[1] = float(normalLevels.size() / 4);
  std::memcpy(p.normalLevels, normalLevels.data(), normalLevels.size() * sizeof(uint32_t));
  p.pageGrid[0] = pages.cellsX, p.pageGrid[1] = pages.cellsZ, p.pageGrid[2] = pages.pagesX;
  std::memcpy(out, &p, sizeof p);
}

}  // namespace

GpuRaycast::GpuRaycast(Context& ctx, const Heightfield& hf, const GpuRaycastOptions& options) : ctx_(ctx), timer_(ctx) {
  double_ = options.allowDouble && ctx.enabledFeatures.shaderFloat64;
  MaxMipmap mip = buildMaxMipmap(hf);  // the CPU oracle's pyramid, so both skip the same nodes
  for (int k = 0; k < options.testDropLevels && mip.levels.size() > 1; ++k) mip.levels.pop_back();
  samplesX_ = hf.width;
  samplesZ_ = hf.height;
  cellsX_ = mip.levels[0].w;
  cellsZ_ = mip.levels[0].h;
  levels_ = int(mip.levels.size());
  extent_ = hf.extent;
  if (cellsX_ > LB_RAYCAST_MAX_CELLS || cellsZ_ > LB_RAYCAST_MAX_CELLS || levels_ > LB_RAYCAST_MAX_LEVELS)
    throw FeatureMissing("GPU ray cast: terrain of " + std::to_string(hf.width) + " x " + std::to_string(hf.height) +
                         " samples exceeds the shader's " + std::to_string(LB_RAYCAST_MAX_CELLS) + " cells a side");
  // The heights in the renderer's pages (terrain/page_layout.h): the shader finds a cell's corners
  // as the rasterizer's sampling function does.
  pages_ = pageLayout(hf);
  UninitVector<float> paged;  // the one-page case is the host array itself, not copied
  if (pages_.pageCount() > 1) paged = pagedHeights(hf, pages_);
  const UninitVector<float>& heights = pages_.pageCount() > 1 ? paged : hf.h;
  const VkDeviceSize heightBytes = VkDeviceSize(heights.size()) * sizeof(float);
  if (heightBytes > ctx.props.limits.maxStorageBufferRange)
    throw FeatureMissing("GPU ray cast: the terrain's " + std::to_string(heightBytes) +
                         " bytes of heights exceed the device's maxStorageBufferRange (" +
                         std::to_string(ctx.props.limits.maxStorageBufferRange) + ")");

  std::vector<BufferPart> mipLevels;  // every level, level 0 first; offsets in floats
  uint32_t mipFloats = 0;
  for (const MaxMipmap::Level& l : mip.levels) {
    levelTable_.insert(levelTable_.end(), {mipFloats, uint32_t(l.w), uint32_t(l.h), 0u});
    mipLevels.push_back({l.max.data(), VkDeviceSize(l.max.size()) * sizeof(float)});
    mipFloats += uint32_t(l.max.size());
  }
  // The renderer's map where the terrain is the kept one (terrain/terrain_cache.h): seconds at 16385^2.
  const std::shared_ptr<const NormalMap> shared = sharedNormalMap(hf);
  const NormalMap& normals = *shared;
  const MemoryTag measure{GpuResource::Measure};
  heights_ = createBufferWithData(ctx, heights.data(), heightBytes, kStorage, measure);
  mip_ = createBufferWithParts(ctx, mipLevels, kStorage, measure);
  std::vector<BufferPart> normalLevels;  // every level, level 0 first; offsets in uints (two halves each)
  size_t normalHalves = 0;
  for (int k = 0; k < normals.levels(); ++k) {
    const auto& texels = normals.levelTexels(k);
    normalTable_.insert(normalTable_.end(), {uint32_t(normalHalves / 2), uint32_t(normals.levelWidth(k)),
                                             uint32_t(normals.levelHeight(k)), 0u});
    normalLevels.push_back({texels.data(), VkDeviceSize(texels.size()) * sizeof(uint16_t)});
    normalHalves += texels.size();
  }
  normals_ = createBufferWithParts(ctx, normalLevels, kStorage, measure);
  params_ = createBuffer(ctx, sizeof(Params<double>), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true, measure);
  unusedDistance_ = createBuffer(ctx, sizeof(float), kStorage, false, measure);

  const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
  bindings_ = createBindings(ctx,
                             {{LB_RAYCAST_BINDING_HEIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
                              {LB_RAYCAST_BINDING_MIP, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
                              {LB_RAYCAST_BINDING_NORMALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
                              {LB_RAYCAST_BINDING_RGBA, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
                              {LB_RAYCAST_BINDING_DISTANCE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
                              {LB_RAYCAST_BINDING_PARAMS, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs}},
                             cs, 0);
  pipeline_ = createComputePipeline(ctx, bindings_.pipelineLayout, double_ ? "raycast" : "raycast_f32");
}

void GpuRaycast::run(const CameraPose& pose, int width, int height, const Buffer& rgba, const Buffer* distance) {
  const VkDeviceSize pixels = VkDeviceSize(width) * VkDeviceSize(height);
  if (width <= 0 || height <= 0 || rgba.size < pixels * 4 || (distance && distance->size < pixels * 4))
    throw std::invalid_argument("GpuRaycast::run: " + std::to_string(width) + " x " + std::to_string(height) +
                                " pixels need buffers of " + std::to_string(pixels * 4) + " bytes");
  // raycastImage's camera: the same matrices, inverted in double.
  const CameraMatrices cam = cameraMatrices(pose, float(width) / float(height), extent_);
  const glm::dmat4 inv = glm::inverse(glm::dmat4(cam.proj) * glm::dmat4(cam.view));
  const double cw = double(extent_) / double(cellsX_), ch = double(extent_) / double(cellsZ_);
  const int grid[4] = {cellsX_, cellsZ_, levels_, distance ? 1 : 0};
  (double_ ? fillParams<double> : fillParams<float>)(params_.mapped, inv, glm::dvec3(cam.eye), cw, ch, width, height,
                                                     grid, samplesX_, samplesZ_, extent_, levelTable_,
                                                     shadingPixelAngle(cam.proj, height), normalTable_, pages_);

  // Set per run: the output buffers are the caller's. The last run has finished (runOneShot waits).
  const VkDescriptorBufferInfo infos[6] = {{heights_.buffer, 0, VK_WHOLE_SIZE},
                                           {mip_.buffer, 0, VK_WHOLE_SIZE},
                                           {normals_.buffer, 0, VK_WHOLE_SIZE},
                                           {rgba.buffer, 0, pixels * 4},
                                           {distance ? distance->buffer : unusedDistance_.buffer, 0, VK_WHOLE_SIZE},
                                           {params_.buffer, 0, VK_WHOLE_SIZE}};
  const uint32_t slots[6] = {LB_RAYCAST_BINDING_HEIGHTS, LB_RAYCAST_BINDING_MIP,      LB_RAYCAST_BINDING_NORMALS,
                             LB_RAYCAST_BINDING_RGBA,    LB_RAYCAST_BINDING_DISTANCE, LB_RAYCAST_BINDING_PARAMS};
  VkWriteDescriptorSet writes[6];
  for (int i = 0; i < 6; ++i) {
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = bindings_.set;
    writes[i].dstBinding = slots[i];
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = i == 5 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(ctx_.device, 6, writes, 0, nullptr);

  runOneShot(ctx_, [&](VkCommandBuffer cmd) {
    // Earlier work on the caller's buffers (or their last read) ends before the shader writes them.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    timer_.begin(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, bindings_.pipelineLayout, 0, 1, &bindings_.set, 0,
                            nullptr);
    vkCmdDispatch(cmd, uint32_t((width + LB_RAYCAST_GROUP - 1) / LB_RAYCAST_GROUP),
                  uint32_t((height + LB_RAYCAST_GROUP - 1) / LB_RAYCAST_GROUP), 1);
    timer_.end(cmd);
    // The caller reads the results on the device (any stage) or, from host-visible buffers, on the host.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
                  VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT | VK_ACCESS_2_HOST_READ_BIT);
  });
  lastGpuMs_ = timer_.ms();
}

RgbaImage GpuRaycast::image(const CameraPose& pose, int width, int height, std::vector<float>* distance) {
  const VkDeviceSize bytes = VkDeviceSize(width > 0 ? width : 0) * VkDeviceSize(height > 0 ? height : 0) * 4;
  Buffer rgba = createBuffer(ctx_, bytes ? bytes : 4, kStorage, true, {GpuResource::Measure});
  Buffer dist;
  if (distance) dist = createBuffer(ctx_, bytes ? bytes : 4, kStorage, true, {GpuResource::Measure});
  run(pose, width, height, rgba, distance ? &dist : nullptr);
  RgbaImage img{width, height, std::vector<uint8_t>(size_t(bytes))};
  std::memcpy(img.px.data(), rgba.mapped, size_t(bytes));
  if (distance) {
    distance->resize(size_t(bytes / 4));
    std::memcpy(distance->data(), dist.mapped, size_t(bytes));
  }
  return img;
}

}  // namespace lb
