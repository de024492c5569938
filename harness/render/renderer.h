#pragma once
// The one renderer shared by every scheme, its frame core: offscreen targets, frame uniforms,
// pipelines by render mode, the measurement passes, and a ring of frames in flight whose queries
// are read after each frame's fence without stalling the next. What differs between draw paths is
// the scheme's PathDrawer (render/path_drawer.h), which the core never asks which path it is.
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <vector>

#include "render/device_terrain.h"
#include "render/frame_data.h"
#include "render/frame_slot.h"
#include "render/gpu_profiler.h"
#include "render/path_drawer.h"
#include "render/scheme.h"
#include "vk/resources.h"

namespace lb {

struct Context;
struct Heightfield;
struct CameraPose;
struct FrameUniforms;
class LodState;

class Renderer {
 public:
  Renderer(Context& ctx, const Heightfield& terrain, const RenderSettings& settings);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Builds the scheme's draw path, pipelines and preprocessing; waits for frames in flight first.
  void setScheme(const Scheme& scheme, const ParamValues& params);
  using SetupCosts = lb::SetupCosts;  // render/frame_data.h
  const SetupCosts& setupCosts() const { return setupCosts_; }
  // New parameter values without rebuilding the path, pipelines or preprocessing: only for those that
  // reach the shaders through the uniforms alone, maxLevel unchanged (replay/surplus.h's max_error_px).
  void setUniformParams(const ParamValues& given);
  // Records and submits a frame. `lod` is the camera the LOD decision uses (normally == view).
  void submitFrame(int frameIndex, const CameraPose& view, const CameraPose& lod, RenderMode mode = RenderMode::Shaded,
                   bool capture = false);
  // Results of frames whose fences have been waited on, in submission order.
  std::vector<FrameResult> takeCompleted();
  void finish();  // wait for every frame in flight

  // Renders one frame synchronously and returns RGBA8 pixels (width * height * 4).
  std::vector<uint8_t> renderImage(const CameraPose& view, const CameraPose& lod, RenderMode mode,
                                   FrameResult* result = nullptr);
  // The same frame copied into `target` (a device buffer of width * height * 4 bytes or more, with
  // TRANSFER_DST usage) instead of host memory, for statistics reduced on the GPU; null: host memory.
  void renderInto(const CameraPose& view, const CameraPose& lod, RenderMode mode, const Buffer* target,
                  FrameResult* result = nullptr);
  // Per patch: outer[4], inner[2] written by the control shader in the last capture frame.
  std::vector<float> capturedLevels();
  using CullCamera = lb::CullCamera;  // render/frame_data.h
  void setCullCamera(CullCamera c) { cullCamera_ = c; }
  CullCamera cullCamera() const { return cullCamera_; }
  // RenderSettings::sky for the frames submitted from now on (images for people between measurements).
  void setSky(bool on) { settings_.sky = on; }
  // Measurement passes, separate from timing frames (each waits for frames in flight).
  // keepMesh false: a path with instances still captures its drawn mesh on the device (the capture
  // grows as it would) but leaves capturedMesh() empty, for a caller that reads no mesh.
  TriangleHistogram measureHistogram(const CameraPose& view, const CameraPose& lod, FrameResult* result = nullptr,
                                     bool keepMesh = true);
  std::vector<float> renderErrorMap(const CameraPose& view, const CameraPose& lod);
  // The scheme texture (CPU preprocessing or compute pass output) read back from the GPU; for a
  // scheme with a per-sample map, that map (one channel, row-major over the samples).
  SchemeTexture readSchemeTexture();

  const RenderSettings& settings() const { return settings_; }
  const ParamValues& params() const { return params_; }  // resolved: defaults filled in
  DrawPath path() const { return scheme_ ? scheme_->info().path : DrawPath::Tessellation; }
  uint32_t patchCount() const { return path_ ? path_->patchCount() : 0; }  // tessellation path: patches
  uint32_t patchesPerDraw() const { return path_ ? path_->patchesPerDraw() : 1; }
  uint32_t drawCount() const { return (patchCount() + patchesPerDraw() - 1) / patchesPerDraw(); }
  // Instanced path: the selection of the last frame submitted (its counters feed countFrame).
  const Selection& lastSelection() const;
  // The LOD state the path keeps across frames (GPU-indirect: replay/lod_replay.h); throws
  // std::logic_error where the path keeps none.
  LodState& lodState();
  bool hasLodState() const { return path_ && path_->lodState(); }
  bool statefulLod() const;  // GpuLod::convergeLimit > 0: measured by replaying its updates
  // Paths with instances: every triangle's three world vertices the last measureHistogram drew
  // (captured by its geometry shader); empty on the tessellation path and after keepMesh false.
  // Throws FeatureMissing when the last histogram pass drew more triangles than the capture holds
  // (its counts and histogram are whole; only the mesh is left out).
  const std::vector<glm::vec3>& capturedMesh() const;
  // Device memory this renderer and its path hold now, by resource (vk/gpu_memory.h): what a case's
  // summary.memory records.
  // The terrain's copy (heights, normal map) counts in full, kept from an earlier renderer or not.
  GpuMemoryAccount gpuMemory() const;

 private:
  using Slot = FrameSlot;  // render/frame_slot.h
  static constexpr int kSlots = 2;

  void createTargets();
  void createDescriptors();
  void bindPathBuffers();  // the path's buffers, or placeholders, and the mesh capture
  VkPipeline pipeline(RenderMode mode, bool capture);
  void record(Slot& slot, int slotIndex, RenderMode mode, bool capture);
  void beginTargets(VkCommandBuffer cmd, RenderMode mode);
  void beginRendering(VkCommandBuffer cmd, RenderMode mode);
  void copyToReadback(VkCommandBuffer cmd, const Slot& slot, const Image& target);
  void collect(int slotIndex);
  FrameUniforms fillUniforms(int slotIndex, const CameraPose& view, const CameraPose& lod);
  void prepareFrame(int slotIndex, const CameraPose& view, const CameraPose& lod);  // uniforms, the path's prepare
  void prepareMeshCapture(uint64_t triangles);
  MemoryTag tag(GpuResource r) { return {r, &memory_}; }

  // Every Vulkan object below is owned by a vk::Unique (directly or through Buffer, Image, Bindings
  // and the path): when the constructor throws half-way, the members built so far release theirs.
  Context& ctx_;
  GpuMemoryAccount memory_;  // before every buffer and image: they give their charges back to it
  const Heightfield& terrain_;
  RenderSettings settings_;
  const Scheme* scheme_ = nullptr;
  ParamValues params_;
  Image color_, errorTarget_, depth_, schemeTex_;
  // The heightfield's pages and their table, the normal map (render/device_terrain.h).
  std::shared_ptr<const DeviceTerrain> terrainCopy_;
  int schemeTexChannels_ = 4;     // SchemeTexture::channels of schemeTex_ (1: R32_SFLOAT)
  std::vector<Image> sampleMap_;  // the scheme's per-sample map in the heights' pages (render/sample_map_pages.h)
  SetupCosts setupCosts_;
  Buffer histogram_, readback_, uniforms_;
  VkDeviceSize uniformStride_ = 0;
  vk::Unique<VkSampler> sampler_;
  Bindings bindings_;
  std::map<int, vk::Unique<VkPipeline>> pipelines_;  // key: mode * 2 + capture
  vk::Unique<VkCommandPool> commandPool_;
  GpuProfiler profiler_;
  std::array<Slot, kSlots> slots_{};
  int nextSlot_ = 0;
  std::vector<int> order_;  // slots in submission order
  std::vector<FrameResult> completed_;
  double lastSubmitMs_ = -1;
  CullCamera cullCamera_ = CullCamera::Lod;
  std::unique_ptr<PathDrawer> path_;
  bool meshStages_ = false;             // the path's stages are task and mesh shaders (GeometryStages::mesh)
  std::array<Buffer, 7> placeholders_;  // for the PathBuffers a path leaves null
  // The mesh capture of measurement passes (LB_BINDING_MESH): room for meshCapacity_ triangles.
  Buffer mesh_;
  uint32_t meshCapacity_ = 0;
  uint64_t meshAtLeast_ = 0;  // triangles a histogram pass drew past the capture's room: the next one's least
  uint64_t meshLost_ = 0;     // triangles the last histogram pass drew past the largest capture (0: none)
  bool captureMeshNext_ = false;
  uint32_t meshCaptureMost() const;
  std::vector<glm::vec3> capturedMesh_;
};

}  // namespace lb
