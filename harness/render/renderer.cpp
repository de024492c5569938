// The frame loop: uniforms, command recording with split draws, queries read after the fence.
#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>

#include "camera/camera_path.h"
#include "render/compute_pass.h"
#include "render/image_io.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace lb {

static double nowMs() {
  using namespace std::chrono;
  return duration<double, std::milli>(steady_clock::now().time_since_epoch()).count();
}

CameraMatrices cameraMatrices(const CameraPose& pose, float aspect, float extent) {
  CameraMatrices m;
  m.eye = pose.eye;
  glm::vec3 dir = pose.target - pose.eye;
  // Looking straight down makes lookAt's up vector degenerate; pick another one then.
  glm::vec3 up = std::abs(glm::normalize(dir).y) > 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  m.view = glm::lookAt(pose.eye, pose.target, up);
  m.proj = glm::perspective(glm::radians(pose.fovDeg), aspect, extent * 1e-4f, extent * 4.0f);
  m.proj[1][1] *= -1.0f;  // Vulkan clip space has y down
  return m;
}

void frustumPlanes(const glm::mat4& vp, glm::vec4 planes[6]) {
  glm::vec4 r0(vp[0][0], vp[1][0], vp[2][0], vp[3][0]), r1(vp[0][1], vp[1][1], vp[2][1], vp[3][1]),
      r2(vp[0][2], vp[1][2], vp[2][2], vp[3][2]), r3(vp[0][3], vp[1][3], vp[2][3], vp[3][3]);
  planes[0] = r3 + r0;
  planes[1] = r3 - r0;
  planes[2] = r3 + r1;
  planes[3] = r3 - r1;
  planes[4] = r2;  // depth in [0,1]
  planes[5] = r3 - r2;
  for (int i = 0; i < 6; ++i) planes[i] /= glm::length(glm::vec3(planes[i]));
}

void Renderer::fillUniforms(int slotIndex, const CameraPose& view, const CameraPose& lod) {
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
  scheme_->update(u, params_);
  std::memcpy(static_cast<char*>(uniforms_.mapped) + uniformStride_ * VkDeviceSize(slotIndex), &u, sizeof u);
  if (lod_) selectInstances(slots_[size_t(slotIndex)], slotIndex, u);
  // The GPU decides how many instances: room for as many as the passes may write.
  if (gpuIndirect_ && captureMeshNext_)
    prepareMeshCapture(
        uint64_t(lodFrozen_ ? lastLodInstances_ : gpuLod_.maxInstances) *
        (gpuLod_.trianglesPerInstance > 0 ? gpuLod_.trianglesPerInstance : footprintRanges_[0].indexCount / 3));
}

void Renderer::prepareMeshCapture(uint64_t triangles) {
  if (triangles > meshCapacity_) {  // measurement passes run after finish(): nothing reads the old buffer
    meshCapacity_ = uint32_t(std::min<uint64_t>(triangles + triangles / 4, 0x7fffffffu / 48));
    if (triangles > meshCapacity_) throw std::runtime_error("mesh capture: too many triangles to capture");
    mesh_ = createBuffer(ctx_, 16 + VkDeviceSize(meshCapacity_) * 48, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    writeInstanceDescriptors();
  }
  auto* head = static_cast<uint32_t*>(mesh_.mapped);
  head[0] = 0;
  head[1] = meshCapacity_;
}

void Renderer::selectInstances(Slot& slot, int slotIndex, const FrameUniforms& u) {
  const double start = nowMs();
  selection_.countersWanted = slot.readback || captureMeshNext_;
  lod_->select(u, selection_);
  if (selection_.instances.size() != footprintRanges_.size())
    throw std::logic_error("scheme '" + scheme_->info().name + "' selected instances for " +
                           std::to_string(selection_.instances.size()) + " footprints, it has " +
                           std::to_string(footprintRanges_.size()));
  const size_t total = selection_.instanceCount();
  if (total > instanceCapacity_) {
    // Frames in flight read the old buffer: wait for them (rare: the capacity only grows).
    finish();
    instanceCapacity_ = uint32_t(std::max<size_t>(256, total + total / 2));
    instances_ = createBuffer(ctx_, VkDeviceSize(sizeof(InstanceRecord)) * instanceCapacity_ * kSlots,
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    writeInstanceDescriptors();
  }
  // Each slot owns a region; draws reach it through firstInstance, which gl_InstanceIndex includes.
  auto* out = static_cast<InstanceRecord*>(instances_.mapped) + size_t(slotIndex) * instanceCapacity_;
  slot.instFirst.assign(footprintRanges_.size(), 0);
  slot.instCount.assign(footprintRanges_.size(), 0);
  uint32_t next = uint32_t(slotIndex) * instanceCapacity_;
  uint64_t triangles = 0;
  for (size_t f = 0; f < footprintRanges_.size(); ++f) {
    const auto& records = selection_.instances[f];
    if (!records.empty())  // an empty vector's data() may be null, which memcpy must not get
      std::memcpy(out, records.data(), records.size() * sizeof(InstanceRecord));
    out += records.size();
    slot.instFirst[f] = next;
    slot.instCount[f] = uint32_t(records.size());
    next += uint32_t(records.size());
    triangles += uint64_t(records.size()) * (footprintRanges_[f].indexCount / 3);
  }
  if (captureMeshNext_) prepareMeshCapture(triangles);
  slot.lodCpuMs = nowMs() - start;
}

void Renderer::drawInstances(VkCommandBuffer cmd, const Slot& slot) {
  for (size_t f = 0; f < footprintRanges_.size(); ++f)
    if (slot.instCount[f] > 0)
      vkCmdDrawIndexed(cmd, footprintRanges_[f].indexCount, slot.instCount[f], footprintRanges_[f].firstIndex,
                       footprintRanges_[f].vertexOffset, slot.instFirst[f]);
}

void Renderer::record(Slot& slot, int slotIndex, RenderMode mode, bool capture) {
  VkPipeline pipe = pipeline(mode, capture);
  VkCommandBuffer cmd = slot.cmd;
  VK_CHECK(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
  profiler_.reset(cmd, slotIndex);
  const Image& target = mode == RenderMode::Error ? errorTarget_ : color_;
  const bool colour = mode != RenderMode::Depth && mode != RenderMode::Frontend;
  const bool depth = mode != RenderMode::Frontend;  // frontend discards all primitives: no attachments
  // Earlier frames may still write these targets: order after them, discard old contents.
  if (colour)
    imageBarrier(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT,
                 VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  if (depth)
    imageBarrier(cmd, depth_.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                 VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
  VkRenderingAttachmentInfo ca{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  ca.imageView = target.view;
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

  uint32_t dynOffset = uint32_t(uniformStride_ * VkDeviceSize(slotIndex));
  profiler_.timestampTop(cmd, slotIndex);
  // The LOD timestamp closes the LOD work: the GPU-indirect path's compute passes, or nothing on the
  // instanced path, whose selection ran on the CPU before this frame (FrameResult::lodCpuMs).
  const bool instanced = lod_ != nullptr || gpuIndirect_;
  if (gpuIndirect_ && !lodFrozen_) recordLodPasses(cmd, dynOffset);
  if (instanced) profiler_.timestampLod(cmd, slotIndex);
  vkCmdBeginRendering(cmd, &ri);
  // Inside the render pass: counts the draws only (no attachment load/clear work), and lets the
  // planted slowdown below draw after the query ends.
  VkDeviceSize zero = 0;
  // Split so no draw can exceed kMaxVerticesPerDraw tessellated vertices or kMaxIndicesPerDraw indices.
  auto drawAll = [&](VkPipeline p) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bindings_.pipelineLayout, 0, 1, &bindings_.set, 1,
                            &dynOffset);
    vkCmdBindVertexBuffers(cmd, 0, 1, vertices_.buffer.ptr(), &zero);
    vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
    if (gpuIndirect_) {
      drawLod(cmd);
      return;
    }
    if (instanced) {
      drawInstances(cmd, slot);
      return;
    }
    for (uint32_t first = 0; first < patchCount_; first += patchesPerDraw_) {
      uint32_t count = std::min(patchesPerDraw_, patchCount_ - first);
      DrawPush push{first};
      vkCmdPushConstants(cmd, bindings_.pipelineLayout, VK_SHADER_STAGE_ALL_GRAPHICS | VK_SHADER_STAGE_COMPUTE_BIT, 0,
                         sizeof push, &push);
      vkCmdDrawIndexed(cmd, count * controlPoints_, 1, first * controlPoints_, 0, 0);
    }
  };
  // A wireframe alone is a solid mesh of lines at small sizes: its lines are blended over the
  // shaded frame, drawn first (outside the statistics query, so the counters are one frame's).
  if (mode == RenderMode::Wireframe) drawAll(pipeline(RenderMode::Shaded, false));
  profiler_.beginStats(cmd, slotIndex);
  drawAll(pipe);
  profiler_.endStats(cmd, slotIndex);
  // The planted slowdown (tests of the regression gate) covers the tessellation and instanced paths;
  // the GPU-indirect path's instance count is the GPU's, so it has none.
  const bool planted =
      settings_.testSlowdown > 0 && mode == RenderMode::Shaded && !capture && !slot.readback && !gpuIndirect_;
  if (planted && instanced) {
    // Planted regression on the instanced path: the first fraction of every footprint's instances again.
    const double s = std::min(1.0, settings_.testSlowdown);
    for (size_t f = 0; f < footprintRanges_.size(); ++f) {
      uint32_t n = uint32_t(std::floor(slot.instCount[f] * s));
      if (n > 0)
        vkCmdDrawIndexed(cmd, footprintRanges_[f].indexCount, n, footprintRanges_[f].firstIndex,
                         footprintRanges_[f].vertexOffset, slot.instFirst[f]);
    }
  } else if (planted) {
    // Planted regression (tests only), after the statistics query and before the closing timestamp:
    // the first fraction s of each eighth of the patches is drawn again (the share spreads over the
    // grid), split like the draws above, so GPU time grows by about s while the counters stay exact.
    const double s = std::min(1.0, settings_.testSlowdown);
    constexpr uint32_t kBlocks = 8;
    for (uint32_t b = 0; b < kBlocks; ++b) {
      uint32_t begin = patchCount_ * b / kBlocks, end = patchCount_ * (b + 1) / kBlocks;
      uint32_t last = begin + uint32_t(std::floor(end * s) - std::floor(begin * s));  // floor(s * patches) in all
      for (uint32_t first = begin; first < last; first += patchesPerDraw_) {
        uint32_t count = std::min(patchesPerDraw_, last - first);
        DrawPush push{first};
        vkCmdPushConstants(cmd, bindings_.pipelineLayout, VK_SHADER_STAGE_ALL_GRAPHICS | VK_SHADER_STAGE_COMPUTE_BIT, 0,
                           sizeof push, &push);
        vkCmdDrawIndexed(cmd, count * controlPoints_, 1, first * controlPoints_, 0, 0);
      }
    }
  }
  // A control scheme's planted multiple (SchemeInfo::drawRepeat): the whole frame again.
  if (scheme_ && scheme_->info().drawRepeat > 1 && mode == RenderMode::Shaded && !capture && !slot.readback)
    for (int k = 1; k < scheme_->info().drawRepeat; ++k) drawAll(pipe);
  vkCmdEndRendering(cmd);
  profiler_.timestampBottom(cmd, slotIndex);
  if (gpuIndirect_) {  // the arguments the passes wrote, for FrameResult::instances
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT,
                  VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    copyLodArgs(cmd, slotIndex);
  }
  if (slot.readback) {
    imageBarrier(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {uint32_t(settings_.width), uint32_t(settings_.height), 1};
    VkBuffer dst = slot.target ? slot.target->buffer : readback_.buffer;
    vkCmdCopyImageToBuffer(cmd, target.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, 1, &region);
  }
  if (capture || mode == RenderMode::Histogram) {
    // The geometry stage may only be named where the device enables geometry shaders.
    VkPipelineStageFlags2 writers =
        instanced ? VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT : VK_PIPELINE_STAGE_2_TESSELLATION_CONTROL_SHADER_BIT;
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
  if (!scheme_) throw std::runtime_error("Renderer::submitFrame before setScheme");
  double start = nowMs();
  int si = nextSlot_;
  nextSlot_ = (nextSlot_ + 1) % kSlots;
  Slot& slot = slots_[size_t(si)];
  if (slot.busy) collect(si);  // the frame kSlots ago; the one just before keeps running
  double ownStart = nowMs();   // the harness's own cost starts after the wait for the old frame
  fillUniforms(si, view, lod);
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
  if (gpuIndirect_) {
    const LodDrawn drawn = lodDrawn(si);
    r.instances = drawn.instances;
    r.draws = drawn.draws;
  } else if (lod_) {
    r.lodCpuMs = slot.lodCpuMs;
    for (uint32_t n : slot.instCount) {
      r.instances += n;
      r.draws += n > 0 ? 1 : 0;
    }
  } else {
    r.draws = drawCount();
  }
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

uint64_t TriangleHistogram::total() const {
  uint64_t t = offscreen + backfacing;
  for (uint64_t b : bins) t += b;
  return t;
}

TriangleHistogram Renderer::measureHistogram(const CameraPose& view, const CameraPose& lod, FrameResult* result) {
  finish();
  std::memset(histogram_.mapped, 0, size_t(histogram_.size));
  captureMeshNext_ = lod_ != nullptr || gpuIndirect_;
  submitFrame(-1, view, lod, RenderMode::Histogram);
  finish();
  captureMeshNext_ = false;
  capturedMesh_.clear();
  if (lod_ || gpuIndirect_) {
    const auto* head = static_cast<const uint32_t*>(mesh_.mapped);
    if (head[0] > head[1])
      throw std::logic_error("mesh capture: " + std::to_string(head[0]) + " triangles drawn, room for " +
                             std::to_string(head[1]));
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
  const auto* p = static_cast<const float*>(capture_.mapped);
  return std::vector<float>(p, p + capture_.size / sizeof(float));
}

SchemeTexture Renderer::readSchemeTexture() {
  finish();
  return {int(schemeTex_.width), int(schemeTex_.height), readImageRgba32f(ctx_, schemeTex_, schemeTexChannels_),
          schemeTexChannels_};
}

}  // namespace lb
