#pragma once
// The scheme interface (docs/design.md, Schemes): everything that differs between LOD methods.
// Terrain, camera, shading and instrumentation belong to the renderer and are shared.
#include <functional>
#include <glm/vec2.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "render/instanced.h"

namespace lb {

struct FrameUniforms;
struct Heightfield;

enum class Topology { Quad4, Quad12, Tri3 };
// How a scheme's triangles reach the rasterizer (docs/draw-paths.md). Tessellation: patches of the
// base grid through the scheme's control shader. InstancedGrid: CPU-selected instances of a few
// index meshes (render/instanced.h) through the scheme's vertex shader. GpuIndirect: instances and
// draw arguments written by the scheme's compute passes on the GPU (GpuLod), drawn indirectly.
// Mesh: task and mesh shaders (VK_EXT_mesh_shader, where the device has it) amplify the LOD of
// one of the other three paths (SchemeInfo::meshLod), so a scheme and its mesh twin differ only in
// how their triangles are made.
enum class DrawPath { Tessellation, InstancedGrid, GpuIndirect, Mesh };
enum class Partitioning { Integer, FractionalEven, FractionalOdd };

struct ParamSpec {
  std::string name;
  int slot = -1;  // index in FrameUniforms::params: LB_<SCHEME>_<PARAM> from shaders/<scheme>_params.h
  double defaultValue = 0;
  double min = 0, max = 0;
  bool integer = false;
  std::string help;
};

// What the harness may read into a scheme's main parameter beyond "the knob a sweep turns".
enum class MainParamRole {
  Knob,             // trades quality for cost in no unit the harness uses
  TriangleWidthPx,  // target triangle width in pixels: the triangle histogram's target area is width^2 / 2
  ErrorBoundPx,     // guaranteed screen-space error in pixels: the surplus metric bisects it
  UniformLevel,     // the one level of every edge and interior: the fixed workload of calibration and probes
};

// A per-frame count of the scheme's own, beside the metrics every scheme gets.
struct SchemeCounter {
  std::string frameKey;  // the measured frame's metric (frame JSON, frames CSV column)
  std::string caseKey;   // case summary: the measured frames where it was above 0
  std::string label;     // the report's column for caseKey, after "<scheme>: "
};

struct SchemeInfo {
  std::string name;
  std::string description;        // one line
  std::string seed;               // source document and section it follows
  std::vector<ParamSpec> params;  // each packed into FrameUniforms::params at its slot
  // The parameter that trades quality for cost: a sweep's front varies it and a matched
  // comparison searches it. "" = none (a scheme without parameters).
  std::string mainParam;
  MainParamRole mainParamRole = MainParamRole::Knob;
  // Values of mainParam the default job sweeps (a config entry's "front": true, config/config.h),
  // so each scheme has a front: at least two. Empty for a scheme without a main parameter.
  std::vector<double> front;
  DrawPath path = DrawPath::Tessellation;
  std::string vert;  // InstancedGrid, GpuIndirect: shaders/<vert>.vert (includes terrain_vertex.glsl)
  // Mesh: shaders/<task>.task and shaders/<mesh>.mesh, and whose LOD they draw: Tessellation (the
  // base grid's patches, the LOD decided per patch in the task shader), InstancedGrid (the scheme's
  // CPU selection, instancedLod) or GpuIndirect (the scheme's compute passes and state, gpuLod).
  std::string task, mesh;
  DrawPath meshLod = DrawPath::Tessellation;
  Topology topology = Topology::Quad4;
  Partitioning partitioning = Partitioning::FractionalEven;
  std::string tesc;                   // Tessellation: shader stem, shaders/<tesc>.tesc
  std::string tese = "terrain_quad";  // shared evaluation shader stem
  bool culls = false;                 // may output factor 0 for patches outside the frustum
  // Compute preprocessing: shaders/<compute>.comp writes the scheme texture once in setScheme
  // (instead of preprocess()); empty = none.
  std::string compute;
  // Counted on every measured frame by countFrame(), in this order.
  std::vector<SchemeCounter> counters;
  // Control schemes only (schemes/controls.cpp): a timed shaded frame issues its draws this many
  // times, the copies after the statistics query, so its cost is known to be that multiple of its
  // twin's while its counters and images stay the twin's.
  int drawRepeat = 1;
};

using ParamValues = std::map<std::string, double>;

// Name of the optional 0/1 parameter that switches a scheme to integer partitioning.
constexpr const char* kIntegerParam = "integer";

// Optional preprocessing output a scheme hands to the renderer (bound at LB_BINDING_SCHEME_TEX).
struct SchemeTexture {
  int width = 0, height = 0;
  std::vector<float> rgba;  // width * height * channels
  // 4: R32G32B32A32_SFLOAT; 1: R32_SFLOAT (a per-sample map: 4 bytes a texel instead of 16, so a
  // 16385^2 density map is 1 GiB, not 4 GiB; shaders read .r either way).
  int channels = 4;
};

// Optional per-sample map: one float per heightfield sample (density's). The renderer stores it in
// the heights' pages, the same layout and table (render/sample_map_pages.h), which shaders read
// with sampleMapAt (shaders/sample_map.glsl): a terrain past one image holds it as it holds its
// heights. It asks for a row span at a time as it fills each page, so no whole-terrain copy of the
// map is made on the host. row(z, x0, count, out): samples x0 .. x0 + count - 1 of row z; called
// from several threads at once.
struct SampleMap {
  std::function<void(int z, int x0, int count, float* out)> row;
  explicit operator bool() const { return bool(row); }
};

// Optional base mesh a scheme supplies instead of the renderer's uniform N x N grid (non-uniform
// patch sizes). Patch p uses indices [p * controlPointCount(topology), ...) in this order.
struct PatchGeometry {
  std::vector<glm::vec2> vertices;  // world x, z (or units the scheme's control shader maps to world: sphere-rings)
  std::vector<uint32_t> indices;    // control points of every patch, patch after patch
  std::vector<glm::vec2> bounds;    // per patch (minHeight, maxHeight) for the control shader's culling
  std::vector<float> schemeBuffer;  // optional; bound at LB_BINDING_SCHEME_BUF as std430 floats
  // Vertices in the scheme's own units, which its control shader maps to the world (adding the
  // terrain origin itself): the renderer leaves them unshifted.
  bool schemeUnits = false;
};

struct TextureSize {
  int width = 0, height = 0;
};

class Scheme {
 public:
  virtual ~Scheme() = default;
  virtual const SchemeInfo& info() const = 0;
  // Largest tessellation level the scheme can emit with these parameters (sizes draw splits).
  virtual float maxLevel(const ParamValues&) const { return 64.0f; }
  // Load-time preprocessing on the CPU; empty texture when the scheme needs none.
  virtual SchemeTexture preprocess(const Heightfield&, const ParamValues&) const { return {}; }
  // Load-time per-sample map (SampleMap above); empty when the scheme needs none. It captures the
  // heightfield, which outlives it.
  virtual SampleMap sampleMap(const Heightfield&, const ParamValues&) const { return {}; }
  // The same for a scheme whose table follows the base grid (grid x grid patches); the renderer calls this one.
  virtual SchemeTexture preprocessGrid(const Heightfield& hf, const ParamValues& v, int /*grid*/) const {
    return preprocess(hf, v);
  }
  // Load-time patch layout; no vertices = the renderer's uniform grid. `grid` is
  // RenderSettings::grid, so a scheme's own layout can size its finest patch as extent / grid.
  virtual PatchGeometry patchGeometry(const Heightfield&, const ParamValues&, int /*grid*/) const { return {}; }
  // Size of the texture SchemeInfo::compute writes; the pass runs one workgroup per texel.
  virtual TextureSize computeOutputSize(const Heightfield&) const { return {}; }
  // Checks between parameters that ParamSpec ranges cannot express; throws InputError.
  // Callers run it on resolveParams' result.
  virtual void validate(const ParamValues&) const {}
  // Partitioning in effect: SchemeInfo::partitioning, or Integer where the scheme declares an
  // `integer` parameter (kIntegerParam) and it is 1 (scenario "fast motion": popping under integer
  // vs fractional spacing). The evaluation shader is compiled per partitioning, so nothing else changes.
  virtual Partitioning partitioning(const ParamValues& values) const;
  // Target triangle area in px^2 for screen-space schemes, 0 when the scheme has none. Default:
  // a main parameter of role TriangleWidthPx, t, gives t^2 / 2 (NVIDIA: size 6 -> 18 px).
  virtual double targetAreaPx(const ParamValues& values) const;
  // Per-frame CPU work: packs parameters into the uniform block (override for more: `frame`
  // already holds the frame's cameras and terrain, e.g. sphere-rings centres its rings on lodEye).
  virtual void update(FrameUniforms& frame, const ParamValues& values) const;
  // The patch mesh of patchGeometry() without what only drawing needs (culling bounds, scheme
  // buffer contents): the crack metric finds the shared edges in it. Empty = the uniform grid.
  virtual PatchGeometry patchLayout(const Heightfield&, const ParamValues&, int /*grid*/) const { return {}; }
  // SchemeInfo::counters of one measured frame, one value each, from its captured levels
  // (Renderer::capturedLevels(): LB_CAPTURE_STRIDE floats per patch).
  virtual std::vector<double> countFrame(const std::vector<float>& /*levels*/) const { return {}; }
  // For a scheme with a compute pre-pass (SchemeInfo::compute): the CPU reference of the texture
  // the pass writes, so load-time costs can be measured without a device. Empty = none.
  virtual SchemeTexture computeReference(const Heightfield&, const ParamValues&) const { return {}; }
  // DrawPath::InstancedGrid: the per-terrain LOD state (footprints, trees, tables) that selects
  // each frame's instances on the CPU. Built once per setScheme.
  virtual std::unique_ptr<InstancedLod> instancedLod(const Heightfield&, const ParamValues&) const { return nullptr; }
  // DrawPath::GpuIndirect: the footprint, the initial LOD state and the compute passes; the records'
  // capacity may follow from the view budget and must stay within the device's limits (`budget`).
  virtual GpuLod gpuLod(const Heightfield&, const ParamValues&, const GpuLodBudget& /*budget*/) const { return {}; }
  // DrawPath::Mesh: the words its mesh shader reads at LB_BINDING_MESH_TABLE (sphere-ms: the
  // tessellation patterns' strip table); empty = none.
  virtual std::vector<uint32_t> meshTable() const { return {}; }
};

// Fills defaults, rejects unknown names and out-of-range values with a message naming them.
ParamValues resolveParams(const SchemeInfo& info, const ParamValues& given);
// For Scheme::validate: throws InputError unless values[lo] < values[hi] (or <= when !strict).
void requireOrdered(const std::string& scheme, const ParamValues& values, const std::string& lo, const std::string& hi,
                    bool strict);
// A one-channel preprocessing texture holding `red` (moved in, not copied).
SchemeTexture redTexture(int width, int height, std::vector<float> red);
const char* partitioningName(Partitioning p);
// The scheme draws the renderer's patch grid (its `grid` setting matters): the tessellation path,
// and a mesh path whose task shader decides the LOD per patch.
bool drawsPatchGrid(const SchemeInfo& info);
const char* topologyName(Topology t);

}  // namespace lb
