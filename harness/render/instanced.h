#pragma once
// The instanced-grid draw path (docs/draw-paths.md): a scheme that decides its LOD on the CPU hands
// the renderer a few index meshes ("footprints") once, and every frame the instances of each; the
// renderer draws each footprint with one instanced indexed draw. No tessellation stage runs.
//
// Lattice units: footprint vertices and instance placements are integers (held exactly in float)
// counted in the finest cell of the scheme, c = extent / ((samples - 1) * cells_per_texel) along
// each axis, terrain-local (the terrain origin is added on the GPU). A vertex shared by two
// instances is therefore computed from the same integers on both sides and is bit-identical.
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <utility>
#include <vector>

namespace lb {

struct FrameUniforms;

// One index mesh, triangle list, in lattice units relative to its instance's placement.
struct Footprint {
  std::string name;                 // for listings and errors ("block", "fixup", "trim", ...)
  std::vector<glm::vec2> vertices;  // integer lattice coordinates
  std::vector<uint32_t> indices;    // triangle list
};

// What the scheme's vertex shader reads at gl_InstanceIndex (shaders/terrain_vertex.glsl
// LB_BINDING_INSTANCES): two vec4 whose meaning belongs to the scheme.
struct InstanceRecord {
  glm::vec4 a{0.0f}, b{0.0f};
};
static_assert(sizeof(InstanceRecord) == 32, "std430 mirror of shaders/terrain_vertex.glsl InstanceRecord");

// One frame's selection: the instances of every footprint (same order as footprints()), and the
// scheme's own per-frame counts in SchemeInfo::counters order.
struct Selection {
  std::vector<std::vector<InstanceRecord>> instances;
  std::vector<double> counters;
  // Set by the renderer before select(): only measured frames read the counters, so a scheme may
  // skip a diagnostic that costs more than the selection itself on timed frames (leaving NaN).
  bool countersWanted = true;
  size_t instanceCount() const {
    size_t n = 0;
    for (const auto& v : instances) n += v.size();
    return n;
  }
};

// The per-terrain LOD state of an instanced scheme: built once per (terrain, parameters) by
// Scheme::instancedLod (quadtrees, error tables), then asked for a selection every frame.
class InstancedLod {
 public:
  virtual ~InstancedLod() = default;
  virtual const std::vector<Footprint>& footprints() const = 0;
  // From the frame's LOD camera (lodEye, lodView, lodProj), culling frustum, viewport (the LOD
  // resolution) and terrain origin; must depend on nothing else (popping and matched searches
  // re-run it for other cameras). `out` is reused between frames: clear what you fill.
  virtual void select(const FrameUniforms& frame, Selection& out) const = 0;
  // A mesh twin's words at LB_BINDING_MESH_TABLE that follow from the terrain (clusters-ms: the
  // clusters' vertices and triangles), used where the scheme's own Scheme::meshTable is empty.
  virtual std::vector<uint32_t> meshTable() const { return {}; }
};

// The GPU-indirect path: LOD passes in compute, on a state buffer that persists across frames,
// write the instance records (LB_BINDING_INSTANCES) and the indirect draw arguments
// (LB_BINDING_LOD_ARGS: VkDrawIndexedIndirectCommand, five uints); the renderer then draws the one
// footprint with vkCmdDrawIndexedIndirect. Stateful schemes (a subdivision tree updated every
// frame) are measured through the path's LOD state (render/lod_state.h): reset, snapshot, restore.
struct GpuLodPass {
  std::string shader;   // shaders/<shader>.comp, the renderer's descriptor set and push constants
  uint32_t groups = 1;  // workgroups dispatched (x)
  // Specialization constant 0 of the shader (a tree level, say), since the passes get no push
  // constants (render/gpu_indirect_drawer.cpp says why); < 0: the shader declares none.
  int64_t spec = -1;
  // >= 0: dispatched indirectly, VkDispatchIndirectCommand at this word of the state buffer (what
  // an earlier pass or frame wrote there), and `groups` is ignored.
  int64_t indirectWord = -1;
};
// What a GPU-indirect scheme may size its instance records by (render/gpu_indirect_drawer.cpp fills it):
// the view budget, that is the LOD viewport in pixels, and the device's limits on the record
// buffer (one storage buffer, one allocation) and on the workgroups of one dispatch.
struct GpuLodBudget {
  uint32_t viewportWidth = 0, viewportHeight = 0;
  uint64_t maxRecordBytes = UINT64_MAX;     // min(maxStorageBufferRange, maxMemoryAllocationSize)
  uint32_t maxDispatchGroups = UINT32_MAX;  // maxComputeWorkGroupCount[0]
};
struct GpuLod {
  Footprint footprint;                 // the mesh every instance draws (its indices: the args' indexCount)
  std::vector<uint32_t> initialState;  // LB_BINDING_LOD_STATE after a reset
  uint32_t maxInstances = 0;           // room for the records the passes write
  // >= 0: the state word the passes read maxInstances from; LodState::load refuses a state
  // that claims more room than this renderer's buffer has.
  int64_t capacityWord = -1;
  std::vector<GpuLodPass> passes;  // every frame, in order, with barriers between them
  // Stateful schemes (a tree the passes refine a little every frame) set the most updates that may
  // reach a static camera's fixed point: the harness converges, snapshots and replays their state
  // (replay/lod_replay.h). 0: the passes' output depends on the frame alone.
  uint32_t convergeLimit = 0;
  // Indirect draws of the footprint: 1, VkDrawIndexedIndirectCommand at word 0 of LB_BINDING_LOD_ARGS;
  // more (a tessellated footprint split to stay within a device's limits), up to maxDraws commands
  // from word 0 and their count at word 5 maxDraws (vkCmdDrawIndexedIndirectCount).
  uint32_t maxDraws = 1;
  // Triangles one instance becomes (room for the mesh capture); 0: the footprint's own. A patch
  // footprint (a control shader) states what the tessellator makes of it.
  uint32_t trianglesPerInstance = 0;
  // >= 0: the state word where the passes count instances beyond maxInstances, not drawn; the
  // replay of a stateful scheme fails its case when an update leaves it above 0.
  int64_t overflowWord = -1;
  // The state words that are the tree itself (first word, count): converged_state_sha256 hashes
  // these alone, so two equal trees hash equal whatever the header's bookkeeping (update counter,
  // the terrain's height range for culling, capacities). Count 0: the whole state but word 0.
  uint32_t treeFirstWord = 0, treeWordCount = 0;
  // What the state's size follows from (a tree's depth, its bytes), recorded with the case.
  std::vector<std::pair<std::string, double>> facts;
  // A mesh path's draw (DrawPath::Mesh): the state word of the VkDrawMeshTasksIndirectCommandEXT the
  // passes leave, each task workgroup taking up to meshTaskRecords instance records; -1: none.
  int64_t meshTasksWord = -1;
  uint32_t meshTaskRecords = 0;
};

// Finest lattice cell of a terrain of width x height samples at `cellsPerTexel` cells per sample
// spacing, in world units along x and z.
glm::dvec2 latticeCell(float extent, int width, int height, double cellsPerTexel);

}  // namespace lb
