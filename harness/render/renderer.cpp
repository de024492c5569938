// The frame loop: uniforms, command recording around the draw path's draws, queries read after
// the fence, and the measurement passes' read-backs.
#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "camera/camera_matrices.h"
#include "camera/camera_path.h"
#include "error.h"
#include "render/compute_pass.h"
#include "render/image_io.h"
#include "render/lod_state.h"
#include "render/sample_map_pages.h"
#include "shaders/footprint.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace lb {

static double nowMs() {
  using namespace std::chrono;
  return duration<double, std::milli>(steady_clock::now().time_since_epoch()).count();
}

FrameUniforms Renderer::fillUniforms(int slotIndex, const CameraPose& view, const CameraPose& lod) {
  // The LOD resolution sets the projection and the pixel units, so an image at another size keeps
  // the case's tessellation exactly (RenderSettings::lodWidth).
  const float lodW = float(settings_.lodWidth > 0 ? settings_.lodWidth : settings_.width);
  const float lodH = float(settings_.lodHeight > 0 ? settings_.lodHeight : settings_.height);
  float aspect = lodW / lodH;
  CameraMatrices v = cameraMatrices(view, aspect, terrain_.extent);
  CameraMatrices l = cameraMatrices(lod, aspect, terrain_.extent);
  FrameUniforms u{};
  u.viewProj = v.proj * v.view;
  u.lodView = l.view;
  u.lodProj = l.proj;
  u.lodEye = glm::vec4(l.eye, 1.0f);
  frustumPlanes(cullCamera_ == CullCamera::View ? u.viewProj : l.proj * l.view, u.frustum);
  u.viewport = glm::vec4(lodW, lodH, 1.0f / lodW, 1.0f / lodH);
  u.terrain = glm::vec4(terrain_.extent, float(settings_.grid), float(terrain_.width), float(terrain_.height));
  u.light = glm::vec4(glm::normalize(glm::vec3(0.4f, 0.8f, 0.3f)), 0.0f);
  u.origin = glm::vec4(float(terrain_.originX), float(terrain_.originZ), 0.0f, 0.0f);
  // The view camera and this target's pixel angle: the footprint's normal map level (shaders/footprint.h).
  u.shading = glm::vec4(v.eye, shadingPixelAngle(v.proj, settings_.height));
  scheme_->update(u, params_);
  std::memcpy(static_cast<char*>(uniforms_.mapped) + uniformStride_ * VkDeviceSize(slotIndex), &u, sizeof u);
  return u;
}

void Renderer::prepareFrame(int slotIndex, const CameraPose& view, const CameraPose& lod) {
  const FrameUniforms u = fillUniforms(slotIndex, view, lod);
  Slot& slot = slots_[size_t(slotIndex)];
  const double start = nowMs();
  const uint64_t triangles = path_->prepare(slotIndex, u, slot.readback || captureMeshNext_);
  if (captureMeshNext_) prepareMeshCapture(std::max(triangles, meshAtLeast_));
  slot.prepareMs = nowMs() - start;
}

// The most triangles the capture holds: one storage buffer of at most 2 GiB, 48 bytes a triangle.
uint32_t Renderer::meshCaptureMost() const {
  return settings_.testMeshCaptureMost > 0 ? settings_.testMeshCaptureMost : 0x7fffffffu / 48;
}

void Renderer::prepareMeshCapture(uint64_t triangles) {
  // A frame of more triangles than the largest capture (a fine configuration of a tuned search on
  // a large terrain) still draws and counts them all; only its mesh is left out (meshLost_).
  const uint32_t room = uint32_t(std::min<uint64_t>(triangles + triangles / 4, meshCaptureMost()));
  if (triangles > meshCapacity_ && room > meshCapacity_) {
    meshCapacity_ = room;  // measurement passes run after finish(): nothing reads the old buffer
    mesh_ = createReadBackBuffer(ctx_, 16 + VkDeviceSize(meshCapacity_) * 48, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                 tag(GpuResource::Capture));
    bindPathBuffers();
  }
  auto* head = static_cast<uint32_t*>(mesh_.mapped);
  head[0] = 0;
  head[1] = meshCapacity_;
}

// Earlier frames may still write the targets: order after them, discard old contents.
void Renderer::beginTargets(VkCommandBuffer cmd, RenderMode mode) {
  if (mode != RenderMode::Depth && mode != RenderMode::Frontend)
    imageBarrier(cmd, (mode == RenderMode::Error ? errorTarget_ : color_).image, VK_IMAGE_ASPECT_COLOR_BIT,
                 VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT,
                 VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  if (mode != RenderMode::Frontend)  // frontend discards all primitives: no attachments
    imageBarrier(cmd, depth_.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                 VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
}

void Renderer::beginRendering(VkCommandBuffer cmd, RenderMode mode) {
  const bool colour = mode != RenderMode::Depth && mode != RenderMode::Frontend;
  const bool depth = mode != RenderMode::Frontend;
  VkRenderingAttachmentInfo ca{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  ca.imageView = (mode == RenderMode::Error ? errorTarget_ : color_).view;
  ca.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  ca.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  ca.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  ca.clearValue.color = {{1.0f, 0.0f, 1.0f, 1.0f}};  // magenta: no terrain pixel has it
  if (settings_.sky)                                 // images for people only: crack detection needs the magenta
    ca.clearValue.color = {{kSkyRgba[0] / 255.0f, kSkyRgba[1] / 255.0f, kSkyRgba[2] / 255.0f, 1.0f}};
  if (mode == RenderMode::Error) ca.clearValue.color = {{-1.0f, 0.0f, 0.0f, 0.0f}};  // error is never negative
  VkRenderingAttachmentInfo da{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  da.imageView = depth_.view;
  da.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  da.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  da.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  da.clearValue.depthStencil = {1.0f, 0};
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {uint32_t(settings_.width), uint32_t(settings_.height)}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = colour ? 1 : 0;
  ri.pColorAttachments = colour ? &ca : nullptr;
  ri.pDepthAttachment = depth ? &da : nullptr;
  vkCmdBeginRendering(cmd, &ri);
}

void Renderer::copyToReadback(VkCommandBuffer cmd, const Slot& slot, const Image& target) {
  imageBarrier(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
               VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {uint32_t(settings_.width), uint32_t(settings_.height), 1};
  VkBuffer dst = slot.target ? slot.target->buffer : readback_.buffer;
  vkCmdCopyImageToBuffer(cmd, target.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, 1, &region);
}

void Renderer::record(Slot& slot, int slotIndex, RenderMode mode, bool capture) {
  VkPipeline pipe = pipeline(mode, capture);
  VkCommandBuffer cmd = slot.cmd;
  VK_CHECK(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
  profiler_.reset(cmd, slotIndex);
  beginTargets(cmd, mode);
  uint32_t dynOffset = uint32_t(uniformStride_ * VkDeviceSize(slotIndex));
  profiler_.timestampTop(cmd, slotIndex);
  // The LOD timestamp closes the LOD work (a path's compute passes, or nothing where its LOD ran
  // on the CPU before this frame: FrameResult::lodCpuMs).
  if (path_->lodApart()) {
    path_->recordLod(cmd, dynOffset);
    profiler_.timestampLod(cmd, slotIndex);
  }
  beginRendering(cmd, mode);
  // Inside the render pass: counts the draws only (no attachment load/clear work), and lets the
  // planted slowdown below draw after the query ends.
  auto drawAll = [&](VkPipeline p) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bindings_.pipelineLayout, 0, 1, &bindings_.set, 1,
                            &dynOffset);
    path_->recordDraws(cmd, slotIndex);
  };
  // A wireframe alone is a solid mesh of lines at small sizes: its lines are blended over the
  // shaded frame, drawn first (outside the statistics query, so the counters are one frame's).
  if (mode == RenderMode::Wireframe) drawAll(pipeline(RenderMode::Shaded, false));
  profiler_.beginStats(cmd, slotIndex, meshStages_);
  drawAll(pipe);
  profiler_.endStats(cmd, slotIndex);
  const bool timed = mode == RenderMode::Shaded && !capture && !slot.readback;
  // Planted regression (tests of the regression gate), after the statistics query and before the
  // closing timestamp, so GPU time grows while the counters stay exact.
  if (settings_.testSlowdown > 0 && timed) path_->recordSlowdown(cmd, slotIndex, std::min(1.0, settings_.testSlowdown));
  // A control scheme's planted multiple (SchemeInfo::drawRepeat): the whole frame again.
  if (timed)
    for (int k = 1; k < scheme_->info().drawRepeat; ++k) drawAll(pipe);
  vkCmdEndRendering(cmd);
  profiler_.timestampBottom(cmd, slotIndex);
  path_->recordAfterDraws(cmd, slotIndex);
  if (slot.readback) copyToReadback(cmd, slot, mode == RenderMode::Error ? errorTarget_ : color_);
  if (capture || mode == RenderMode::Histogram) {
    // The geometry stage may only be named where the device enables geometry shaders.
    VkPipelineStageFlags2 writers = path_->stages().storeStage;
    if (ctx_.enabledFeatures.geometryShader) writers |= VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT;
    memoryBarrier(cmd, writers, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                  VK_ACCESS_2_HOST_READ_BIT);
  }
  if (slot.readback) {  // read by the host, or by the compute passes of replay/measure_gpu.h
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_HOST_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_HOST_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  }
  VK_CHECK(vkEndCommandBuffer(cmd));
}

void Renderer::submitFrame(int frameIndex, const CameraPose& view, const CameraPose& lod, RenderMode mode,
                           bool capture) {
  if (!path_) throw std::runtime_error("Renderer::submitFrame before setScheme");
  double start = nowMs();
  int si = nextSlot_;
  nextSlot_ = (nextSlot_ + 1) % kSlots;
  Slot& slot = slots_[size_t(si)];
  if (slot.busy) collect(si);  // the frame kSlots ago; the one just before keeps running
  double ownStart = nowMs();   // the harness's own cost starts after the wait for the old frame
  prepareFrame(si, view, lod);
  record(slot, si, mode, capture);
  VkSubmitInfo sub{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  sub.commandBufferCount = 1;
  sub.pCommandBuffers = &slot.cmd;
  VK_CHECK(vkResetFences(ctx_.device, 1, slot.fence.ptr()));
  VK_CHECK(vkQueueSubmit(ctx_.queue, 1, &sub, slot.fence));
  slot.busy = true;
  slot.frame = frameIndex;
  slot.harnessMs = nowMs() - ownStart;
  slot.cpuMs = lastSubmitMs_ < 0 ? nowMs() - start : start - lastSubmitMs_;
  lastSubmitMs_ = start;
  order_.push_back(si);
}

void Renderer::collect(int si) {
  Slot& slot = slots_[size_t(si)];
  if (!slot.busy) return;
  VK_CHECK(vkWaitForFences(ctx_.device, 1, slot.fence.ptr(), VK_TRUE, UINT64_MAX));
  double readStart = nowMs();
  GpuSample sample = profiler_.read(si);
  FrameResult r;
  r.frame = slot.frame;
  r.gpuMs = sample.gpuMs;
  r.cpuMs = slot.cpuMs;
  r.stats = sample.stats;
  r.lodMs = sample.lodMs;
  r.drawMs = sample.drawMs;
  path_->collect(si, slot.prepareMs, r);
  r.harnessMs = slot.harnessMs + (nowMs() - readStart);
  completed_.push_back(r);
  slot.busy = false;
  order_.erase(std::find(order_.begin(), order_.end(), si));
}

std::vector<FrameResult> Renderer::takeCompleted() {
  std::vector<FrameResult> out;
  out.swap(completed_);
  return out;
}

void Renderer::finish() {
  while (!order_.empty()) collect(order_.front());
  lastSubmitMs_ = -1;
}

std::vector<uint8_t> Renderer::renderImage(const CameraPose& view, const CameraPose& lod, RenderMode mode,
                                           FrameResult* result) {
  renderInto(view, lod, mode, nullptr, result);
  const auto* p = static_cast<const uint8_t*>(readback_.mapped);
  return std::vector<uint8_t>(p, p + readback_.size);
}

void Renderer::renderInto(const CameraPose& view, const CameraPose& lod, RenderMode mode, const Buffer* target,
                          FrameResult* result) {
  if (mode == RenderMode::Depth || mode == RenderMode::Frontend)
    throw std::logic_error("renderImage: timing modes depth and frontend write no colour image");
  if (target && target->size < readback_.size) throw std::logic_error("renderInto: target buffer too small");
  finish();
  int si = nextSlot_;
  slots_[size_t(si)].readback = true;
  slots_[size_t(si)].target = target;
  submitFrame(-1, view, lod, mode, /*capture=*/ctx_.enabledFeatures.vertexPipelineStoresAndAtomics);
  finish();
  slots_[size_t(si)].readback = false;
  slots_[size_t(si)].target = nullptr;
  auto done = takeCompleted();
  if (result && !done.empty()) *result = done.back();
}

TriangleHistogram Renderer::measureHistogram(const CameraPose& view, const CameraPose& lod, FrameResult* result,
                                             bool keepMesh) {
  const bool mesh = path_ && path_->stages().meshCapture;
  // A path whose GPU decides its triangles without a bound the host knows (a mesh path's task
  // shader) may outgrow the capture: it then gets room for what it drew and draws once more.
  for (int attempt = 0;; ++attempt) {
    finish();
    std::memset(histogram_.mapped, 0, size_t(histogram_.size));
    captureMeshNext_ = mesh;
    submitFrame(-1, view, lod, RenderMode::Histogram);
    finish();
    captureMeshNext_ = false;
    const uint32_t drawn = mesh ? static_cast<const uint32_t*>(mesh_.mapped)[0] : 0;
    if (attempt > 0 || drawn <= meshCapacity_) break;
    meshAtLeast_ = drawn;
    takeCompleted();
  }
  capturedMesh_.clear();
  meshLost_ = 0;
  if (mesh) {
    const auto* head = static_cast<const uint32_t*>(mesh_.mapped);
    if (head[0] > head[1] && head[1] < meshCaptureMost())
      throw std::logic_error("mesh capture: " + std::to_string(head[0]) + " triangles drawn, room for " +
                             std::to_string(head[1]));
    if (head[0] > head[1]) meshLost_ = head[0];
  }
  if (mesh && keepMesh &&
      meshLost_ == 0) {  // millions of vertices at 1080p on a large terrain: copied only for a reader
    const auto* head = static_cast<const uint32_t*>(mesh_.mapped);
    const auto* v = reinterpret_cast<const glm::vec4*>(static_cast<const char*>(mesh_.mapped) + 16);
    capturedMesh_.reserve(size_t(head[0]) * 3);
    for (size_t i = 0; i < size_t(head[0]) * 3; ++i) capturedMesh_.emplace_back(v[i]);
  }
  auto done = takeCompleted();
  if (result && !done.empty()) *result = done.back();
  const auto* c = static_cast<const uint32_t*>(histogram_.mapped);
  TriangleHistogram h;
  for (int i = 0; i < LB_HIST_BINS; ++i) h.bins[size_t(i)] = c[i];
  h.offscreen = c[LB_HIST_OFFSCREEN];
  h.backfacing = c[LB_HIST_BACKFACING];
  h.degenerate = c[LB_HIST_DEGENERATE];
  h.areaSum = double((uint64_t(c[LB_HIST_AREA_HI]) << 32) | c[LB_HIST_AREA_LO]) / LB_HIST_AREA_SCALE;
  return h;
}

std::vector<float> Renderer::renderErrorMap(const CameraPose& view, const CameraPose& lod) {
  std::vector<uint8_t> bytes = renderImage(view, lod, RenderMode::Error);
  std::vector<float> px(bytes.size() / sizeof(float));
  std::memcpy(px.data(), bytes.data(), px.size() * sizeof(float));
  return px;
}

std::vector<float> Renderer::capturedLevels() {
  finish();
  const Buffer& capture = path_ && path_->buffers().capture ? *path_->buffers().capture : placeholders_[1];
  const auto* p = static_cast<const float*>(capture.mapped);
  return std::vector<float>(p, p + capture.size / sizeof(float));
}

const std::vector<glm::vec3>& Renderer::capturedMesh() const {
  if (meshLost_ > 0)
    throw FeatureMissing("mesh capture: the frame drew " + std::to_string(meshLost_) +
                         " triangles, the capture holds at most " + std::to_string(meshCaptureMost()) +
                         " (one storage buffer of 2 GiB)");
  return capturedMesh_;
}

SchemeTexture Renderer::readSchemeTexture() {
  finish();
  if (!sampleMap_.empty())
    return {terrain_.width, terrain_.height, readSampleMapPages(ctx_, terrainCopy_->heights, sampleMap_), 1};
  return {int(schemeTex_.width), int(schemeTex_.height), readImageRgba32f(ctx_, schemeTex_, schemeTexChannels_),
          schemeTexChannels_};
}

GpuMemoryAccount Renderer::gpuMemory() const {
  GpuMemoryAccount sum = memory_;
  if (terrainCopy_)
    for (size_t r = 0; r < sum.live.size(); ++r) sum.live[r] += terrainCopy_->memory.live[r];
  return sum;
}

const Selection& Renderer::lastSelection() const {
  static const Selection kNone;
  const Selection* s = path_ ? path_->selection() : nullptr;
  return s ? *s : kNone;
}

LodState& Renderer::lodState() {
  LodState* s = path_ ? path_->lodState() : nullptr;
  if (!s) throw std::logic_error("LOD state hooks: the scheme is not GPU-indirect");
  return *s;
}

bool Renderer::statefulLod() const {
  return hasLodState() && path_->lodState()->gpuLod().convergeLimit > 0;
}

void Renderer::setUniformParams(const ParamValues& given) {
  params_ = resolveParams(scheme_->info(), given);
  scheme_->validate(params_);
}

}  // namespace lb
