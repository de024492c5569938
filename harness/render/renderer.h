#pragma once
// The one renderer shared by every scheme: offscreen colour + depth, one of two draw paths (a base
// grid of N x N tessellated patches, or a scheme's CPU-selected instanced footprints), and a ring of frames in flight
// whose timestamps and pipeline statistics are read after each frame's fence without stalling the next frame.
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "render/gpu_profiler.h"
#include "render/scheme.h"
#include "vk/resources.h"

namespace lb {

struct Context;
struct Heightfield;
struct CameraPose;

// Shaded/Heatmap/Wireframe write RGBA8 (Wireframe: the shaded frame with the tessellation's edges,
// coloured by level, blended over it); Error writes per-pixel screen-space error (R32F, -1 where
// no terrain); Histogram bins triangle areas in a geometry shader and rasterizes nothing.
// Timing modes (sweep/timing_modes.h): Depth rasterizes into depth only (no colour attachment, no
// fragment shader); Frontend discards every primitive before rasterization, so only the vertex,
// LOD decision (control) and tessellator/evaluation stages run.
enum class RenderMode { Shaded = 0, Heatmap = 1, Wireframe = 2, Error = 3, Histogram = 4, Depth = 5, Frontend = 6 };

// Triangle counts by screen-space area (see LB_HIST_* in shaders/shared.h).
struct TriangleHistogram {
  std::array<uint64_t, 15> bins{};  // < 1/8 px, [1/8, 1/4), ..., [512, 1024), >= 1024 px
  uint64_t offscreen = 0, backfacing = 0;
  uint64_t degenerate = 0;  // of all the above: zero area on the ground plane (LB_HIST_DEGENERATE), not an extra bin
  double areaSum = 0;       // exact sum of the binned (on-screen, front-facing) areas in px^2 (1/256 px^2 steps)
  uint64_t total() const;
};

struct RenderSettings {
  int width = 320, height = 180;
  int grid = 32;  // patches per side
  // Testing only (planted regression, in [0, 1]): timing frames draw the first fraction of every
  // eighth of the patches again, after the statistics query ends and before the closing
  // timestamp, so GPU time grows while the counters stay exact (see record()).
  double testSlowdown = 0;
  // Images for people: the resolution the LOD decisions, error pixels and histogram
  // areas assume (0 = width x height). A case's images render its frames at more pixels with the
  // case's own tessellation: lodWidth x lodHeight = the case's resolution (same aspect ratio).
  int lodWidth = 0, lodHeight = 0;
  // Clear colour: magenta (kClearRgba) for measurement and timing frames, or the neutral sky
  // (kSkyRgba, render/image_io.h) for images written for people; never sky where cracks are detected.
  bool sky = false;
  // Testing only: shade with the pre-issue-13 per-pixel normal from four height lookups instead of
  // the normal map (shaders/terrain.frag kHeightNormals); the geometry and counters are the same.
  bool testHeightNormals = false;
};

struct FrameResult {
  int frame = 0;
  double gpuMs = 0;  // timestamps around the terrain draws x timestampPeriod
  double cpuMs = 0;  // host time between consecutive frame submissions
  // The harness's own host cost of the frame: uniform fill, recording, submit, and the read-back
  // of its queries (the fence wait is left out: that is the GPU's time, not the harness's).
  double harnessMs = 0;
  PipelineStats stats;
  // Draw paths whose LOD runs apart from drawing (instanced grid): GPU time of the LOD work and of
  // the draws (GpuSample), and the CPU selection plus its upload (inside harnessMs). -1 = none
  // (tessellation: the LOD decision runs inside the draws).
  double lodMs = -1, drawMs = -1, lodCpuMs = -1;
  uint64_t instances = 0;  // instanced path: instances drawn (all footprints)
  uint32_t draws = 0;      // draw calls of the terrain
};

// Camera matrices in Vulkan conventions (y down in clip space, depth in [0,1]).
struct CameraMatrices {
  glm::mat4 view{1}, proj{1};
  glm::vec3 eye{0};
};
CameraMatrices cameraMatrices(const CameraPose& pose, float aspect, float extent);
void frustumPlanes(const glm::mat4& viewProj, glm::vec4 planes[6]);

// Largest vertex count a single draw may produce (Mesa 22.3 lavapipe: 16-bit tessellator indices).
constexpr uint32_t kMaxVerticesPerDraw = 65535;
// Largest index count of a single draw: Mesa 22.3 lavapipe runs longer draws in 1024-index
// segments and restarts gl_PrimitiveID in each (measured), which breaks patchIndex().
constexpr uint32_t kMaxIndicesPerDraw = 1024;
// Upper bound of vertices one patch can generate at tessellation level `level`.
uint32_t maxVerticesPerPatch(float level, Partitioning partitioning);

class Renderer {
 public:
  Renderer(Context& ctx, const Heightfield& terrain, const RenderSettings& settings);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Builds the scheme's pipelines and preprocessing; waits for frames in flight first.
  void setScheme(const Scheme& scheme, const ParamValues& params);
  // Wall seconds of the load-time work, for run.json costs.terrains: the normal map (CPU, in the
  // constructor) and the last setScheme's preprocessing (CPU preprocess, or the compute pass, with
  // the texture's upload).
  struct SetupCosts {
    double normalMapS = 0, preprocessS = 0;
  };
  const SetupCosts& setupCosts() const { return setupCosts_; }
  // New values for the current scheme's parameters without rebuilding pipelines or preprocessing:
  // only for parameters that reach the shaders through the uniform block alone and leave maxLevel
  // unchanged (errbound's max_error_px in the surplus search, replay/surplus.h).
  void setUniformParams(const ParamValues& given) {
    params_ = resolveParams(scheme_->info(), given);
    scheme_->validate(params_);
  }
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
  // Which camera's frustum the control shaders cull with (FrameUniforms::frustum). Lod (default)
  // follows the design; View keeps culling live while the LOD camera is frozen, so a popping pass
  // (replay/popping.h) sees only level changes, not holes where the old frustum culled.
  enum class CullCamera { Lod, View };
  void setCullCamera(CullCamera c) { cullCamera_ = c; }
  // RenderSettings::sky for the frames submitted from now on (images for people between measurements).
  void setSky(bool on) { settings_.sky = on; }
  CullCamera cullCamera() const { return cullCamera_; }
  // Measurement passes, separate from timing frames (each waits for frames in flight).
  TriangleHistogram measureHistogram(const CameraPose& view, const CameraPose& lod, FrameResult* result = nullptr);
  std::vector<float> renderErrorMap(const CameraPose& view, const CameraPose& lod);
  // The scheme texture (CPU preprocessing or compute pass output) read back from the GPU.
  SchemeTexture readSchemeTexture();

  const RenderSettings& settings() const { return settings_; }
  const ParamValues& params() const { return params_; }  // resolved: defaults filled in
  uint32_t patchCount() const { return patchCount_; }
  uint32_t patchesPerDraw() const { return patchesPerDraw_; }
  uint32_t drawCount() const { return (patchCount_ + patchesPerDraw_ - 1) / patchesPerDraw_; }
  DrawPath path() const { return scheme_ ? scheme_->info().path : DrawPath::Tessellation; }
  // Instanced path: the selection of the last frame submitted (its counters feed countFrame).
  const Selection& lastSelection() const { return selection_; }
  // GPU-indirect path: the LOD state across frames (each waits for frames in flight first). Reset
  // writes the scheme's initial state; snapshot copies the state aside, restore copies it back, so
  // a stateful scheme's repetitions and replays can start from the same state.
  void resetLodState();
  void snapshotLodState();
  void restoreLodState();
  std::vector<uint32_t> readLodState();
  void loadLodState(const std::vector<uint32_t>& words);  // the whole state, e.g. another renderer's
  // Stateful GPU-indirect schemes (GpuLod::convergeLimit > 0) are measured by replaying their
  // updates (replay/lod_replay.h): updateLod runs one frame's LOD passes alone for `pose` and
  // returns the instance count they left; while frozen, frames draw the last update's instances
  // without running the passes, so measurement passes see the state a timed frame drew.
  bool statefulLod() const { return gpuIndirect_ && gpuLod_.convergeLimit > 0; }
  uint32_t convergeLimit() const { return gpuIndirect_ ? gpuLod_.convergeLimit : 0; }
  const std::vector<std::pair<std::string, double>>& gpuLodFacts() const { return gpuLod_.facts; }
  const GpuLod& gpuLod() const { return gpuLod_; }
  uint32_t updateLod(const CameraPose& pose);
  void setLodFrozen(bool frozen) { lodFrozen_ = frozen; }
  // Instances the last updateLod left beyond the record capacity (drawn: none of them).
  uint32_t lodOverflow() const { return lastLodOverflow_; }
  uint32_t lodCapacity() const { return gpuIndirect_ ? gpuLod_.maxInstances : 0; }
  bool lodFrozen() const { return lodFrozen_; }
  // Instanced and GPU-indirect paths: every triangle's three world vertices drawn by the last measureHistogram
  // (captured by the histogram's geometry shader); empty on the tessellation path.
  const std::vector<glm::vec3>& capturedMesh() const { return capturedMesh_; }

 private:
  struct Slot {
    VkCommandBuffer cmd = VK_NULL_HANDLE;  // released with commandPool_
    vk::Unique<VkFence> fence;
    bool busy = false;
    int frame = 0;
    double cpuMs = 0;
    double harnessMs = 0;  // host time spent in submitFrame (uniforms, recording, submit)
    bool readback = false;
    const Buffer* target = nullptr;  // renderInto's destination of the readback copy (null: readback_)
    // Instanced path: this frame's first instance and count per footprint, and its CPU LOD time.
    std::vector<uint32_t> instFirst, instCount;
    double lodCpuMs = -1;
  };
  static constexpr int kSlots = 2;

  void createTargets();
  void createGrid();
  void createDescriptors();
  VkPipeline pipeline(RenderMode mode, bool capture);
  void record(Slot& slot, int slotIndex, RenderMode mode, bool capture);
  void collect(int slotIndex);
  void fillUniforms(int slotIndex, const CameraPose& view, const CameraPose& lod);
  void selectInstances(Slot& slot, int slotIndex, const FrameUniforms& u);
  void createFootprints();
  void writeInstanceDescriptors();
  void drawInstances(VkCommandBuffer cmd, const Slot& slot);
  void minimalPatchBuffers();
  void prepareMeshCapture(uint64_t triangles);
  void createGpuLod();
  void recordLodPasses(VkCommandBuffer cmd, uint32_t dynOffset);
  void copyLodState(const Buffer& from, const Buffer& to);
  size_t argsWords() const;                              // LB_BINDING_LOD_ARGS, in uint32
  void drawLod(VkCommandBuffer cmd);                     // the indirect draw(s) the passes wrote
  void copyLodArgs(VkCommandBuffer cmd, int slotIndex);  // into the slot's readback, for the host
  struct LodDrawn {
    uint32_t instances = 0, draws = 0;
  };
  LodDrawn lodDrawn(int slotIndex) const;  // what those arguments drew

  // Every Vulkan object below is owned by a vk::Unique (directly or through Buffer, Image and
  // Bindings): when the constructor throws half-way, the members built so far release theirs.
  Context& ctx_;
  const Heightfield& terrain_;
  RenderSettings settings_;
  const Scheme* scheme_ = nullptr;
  ParamValues params_;
  Image color_, errorTarget_, depth_, height_, schemeTex_, normalMap_;
  int schemeTexChannels_ = 4;  // SchemeTexture::channels of schemeTex_ (1: R32_SFLOAT)
  SetupCosts setupCosts_;
  Buffer histogram_, readback_, vertices_, indices_, bounds_, capture_, schemeBuf_, uniforms_;
  VkDeviceSize uniformStride_ = 0;
  vk::Unique<VkSampler> sampler_;
  vk::Unique<VkSampler> linearSampler_;  // the normal map's
  Bindings bindings_;
  std::map<int, vk::Unique<VkPipeline>> pipelines_;  // key: mode * 2 + capture
  vk::Unique<VkCommandPool> commandPool_;
  GpuProfiler profiler_;
  std::array<Slot, kSlots> slots_{};
  int nextSlot_ = 0;
  std::vector<int> order_;  // slots in submission order
  std::vector<FrameResult> completed_;
  uint32_t patchCount_ = 0, controlPoints_ = 4, patchesPerDraw_ = 1;
  double lastSubmitMs_ = -1;
  CullCamera cullCamera_ = CullCamera::Lod;
  // Instanced path (render/instanced.h): the scheme's LOD state, each footprint's range in the
  // vertex and index buffers, the instance buffer (kSlots regions of instanceCapacity_ records,
  // host-visible, written in fillUniforms) and the mesh capture of measurement passes.
  struct FootprintRange {
    uint32_t firstIndex = 0, indexCount = 0;
    int32_t vertexOffset = 0;
  };
  std::unique_ptr<InstancedLod> lod_;
  std::vector<FootprintRange> footprintRanges_;
  Selection selection_;
  Buffer instances_, mesh_;
  uint32_t instanceCapacity_ = 0;
  uint32_t meshCapacity_ = 0;  // triangles
  bool captureMeshNext_ = false;
  std::vector<glm::vec3> capturedMesh_;
  // GPU-indirect path (render/instanced.h GpuLod): its passes' pipelines, the state and its
  // snapshot, the draw arguments the passes write, and a per-slot copy of them for the host.
  bool gpuIndirect_ = false;
  GpuLod gpuLod_;
  std::vector<vk::Unique<VkPipeline>> lodPipelines_;
  Buffer lodState_, lodSnapshot_, lodArgs_, lodArgsReadback_;
  bool lodFrozen_ = false;
  uint32_t lastLodInstances_ = 0;  // the instance count the last updateLod left
  uint32_t lastLodOverflow_ = 0;   // and the instances it could not draw (GpuLod::overflowWord)
};

}  // namespace lb
