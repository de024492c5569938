#pragma once
// A draw path is an object (docs/draw-paths.md, "The renderer"): the frame core (render/renderer.h)
// owns the targets, uniforms, pipelines by mode, queries and the ring of frames in flight and never
// asks which path it runs; a PathDrawer owns what differs: its geometry and the buffers it binds,
// its LOD work before the draws, the draws, and what a finished frame drew. One file per path
// (patch_drawer.cpp, instanced_grid_drawer.cpp, gpu_indirect_drawer.cpp, mesh_drawer.cpp), one case in
// makePathDrawer.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "render/frame_data.h"
#include "render/scheme.h"

namespace lb {

struct Bindings;
struct GpuMemoryAccount;
struct Buffer;
struct CameraPose;
struct Context;
struct FrameUniforms;
class LodState;

// A slot's uniforms, filled for a pose outside any frame, and the dynamic offset that selects them.
struct UniformSlot {
  int slot = 0;
  uint32_t dynOffset = 0;
};

// What a path may use of the frame core. The references outlive the path (the renderer owns both).
struct PathEnv {
  Context& ctx;
  const Heightfield& terrain;
  const RenderSettings& settings;
  const Scheme& scheme;
  const ParamValues& params;     // resolved; Renderer::setUniformParams may change uniform-only values
  const Bindings& bindings;      // the one pipeline layout and descriptor set of every pipeline
  int slots = 0;                 // frames in flight: per-slot state is indexed 0 .. slots - 1
  std::function<void()> finish;  // waits for every frame in flight (before a path replaces a buffer they read)
  std::function<void()> rebind;  // writes buffers() into the descriptor set again
  std::function<UniformSlot(const CameraPose&)> uniforms;  // a free slot's uniforms, LOD and view at `pose`
  // The renderer's memory account: a path tags its buffers {resource, memory} (vk/gpu_memory.h).
  GpuMemoryAccount* memory = nullptr;
};

// The stages before rasterization of every pipeline of a path (the frame core adds the fragment
// and histogram stages by mode). No control shader: a triangle list. A mesh shader instead of a
// vertex shader: task (optional) and mesh stages, no vertex input; such a path bins its histogram
// and captures its mesh in the mesh shader, since a mesh pipeline has no geometry stage.
struct GeometryStages {
  std::string vert, tesc, tese;  // SPIR-V file names; tesc is specialized with the level capture
  std::string task, mesh;        // SPIR-V file names; task is specialized with the level capture
  uint32_t controlPoints = 4;
  bool meshCapture = false;  // the histogram pass records the drawn mesh (LB_BINDING_MESH)
  // The stage whose storage writes a capture or histogram frame reads back on the host (besides
  // the geometry shader's, where the device has one).
  VkPipelineStageFlags2 storeStage = VK_PIPELINE_STAGE_2_TESSELLATION_CONTROL_SHADER_BIT;
};

// The buffers a path binds, each at its LB_BINDING_*; null: the frame core binds a placeholder
// (one pipeline layout serves every path, so every binding must hold a buffer).
struct PathBuffers {
  const Buffer *bounds = nullptr, *capture = nullptr, *schemeBuf = nullptr;  // patches
  const Buffer *instances = nullptr, *lodState = nullptr, *lodArgs = nullptr;
  const Buffer* meshTable = nullptr;  // mesh path: the patterns' strip table
};

class PathDrawer {
 public:
  virtual ~PathDrawer() = default;
  virtual GeometryStages stages() const = 0;
  virtual PathBuffers buffers() const = 0;
  // On the CPU before a frame is recorded into `slot`, with its uniforms: the path's CPU LOD work.
  // `measured`: the frame is a measurement, whose counters are read. Returns the triangles the frame
  // may draw, for the frame core's mesh capture (read where stages().meshCapture).
  virtual uint64_t prepare(int /*slot*/, const FrameUniforms& /*u*/, bool /*measured*/) { return 0; }
  // LOD decided apart from the draws: the frame core writes the LOD timestamp after recordLod.
  virtual bool lodApart() const { return false; }
  virtual void recordLod(VkCommandBuffer /*cmd*/, uint32_t /*dynOffset*/) {}
  // Inside the rendering, after the pipeline and the descriptor set are bound.
  virtual void recordDraws(VkCommandBuffer cmd, int slot) = 0;
  // The planted regression of the tests (RenderSettings::testSlowdown): a `share` of the frame's
  // draws again, after the statistics query; nothing where the GPU decides the counts.
  virtual void recordSlowdown(VkCommandBuffer /*cmd*/, int /*slot*/, double /*share*/) {}
  virtual void recordAfterDraws(VkCommandBuffer /*cmd*/, int /*slot*/) {}  // after the closing timestamp
  // After the slot's fence: what its frame drew; `prepareMs` is the host time of its prepare().
  virtual void collect(int slot, double prepareMs, FrameResult& r) const = 0;

  virtual uint32_t patchCount() const { return 0; }
  virtual uint32_t patchesPerDraw() const { return 1; }
  virtual const Selection* selection() const { return nullptr; }  // the last CPU selection
  virtual LodState* lodState() { return nullptr; }                // a state kept across frames
};

std::unique_ptr<PathDrawer> makePathDrawer(const PathEnv& env);
std::unique_ptr<PathDrawer> makePatchDrawer(const PathEnv& env);
std::unique_ptr<PathDrawer> makeInstancedGridDrawer(const PathEnv& env);
std::unique_ptr<PathDrawer> makeGpuIndirectDrawer(const PathEnv& env);
// Throws FeatureMissing where the device has no mesh shaders.
std::unique_ptr<PathDrawer> makeMeshDrawer(const PathEnv& env);

}  // namespace lb
