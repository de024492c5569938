// sphere-ms: sphere's LOD (schemes/sphere.cpp: NVIDIA, "DirectX 11 Terrain Tessellation", Cantlay
// 2011, "Hull Shader: Tessellation LOD") drawn without the tessellator, so sphere against sphere-ms
// is the fixed-function tessellator against a mesh-shader one at one LOD decision. The task shader
// (shaders/sphere_ms.task) makes sphere.tesc's decision for each patch of the same base grid (the
// same corners, height bounds and frustum culling, the same sphere rule in sphere_lod.glsl) and
// rounds each factor as the tessellator's equal_spacing does; the mesh shader
// (shaders/sphere_ms.mesh) emits the patch's pattern from the generator's rules
// (schemes/preprocess/tess_patterns.h, parallel form in shaders/tess_piece.h, its strip table
// uploaded), split into pieces of at most 11 segments a side as the generator splits it. The
// generator's points are equal_spacing's, so the twin is sphere with integer = 1 (fractional_even
// moves points at odd factors): the same vertex set and the same number of triangles at the same
// factors, their connectivity the generator's. docs/draw-paths.md, "The mesh path".
#include "render/scheme.h"
#include "schemes/preprocess/tess_patterns.h"
#include "shaders/sphere_params.h"

namespace lb {
namespace {

class SphereMs : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "sphere-ms",
        .description = "sphere's LOD per patch in a task shader, its integer factors' patterns from a mesh shader",
        .seed =
            "nvidia-dx11-terrain-tessellation-2011: Hull Shader: Tessellation LOD (sphere with integer = 1), "
            "amplified by task and mesh shaders (VK_EXT_mesh_shader)",
        .params = {{"tri_size", LB_SPHERE_TRI_SIZE, 3, 0.5, 64, false,
                    "target triangle width in pixels (g_tessellatedTriSize)"}},
        .mainParam = "tri_size",
        .mainParamRole = MainParamRole::TriangleWidthPx,
        .front = {2, 4, 8},
        .path = DrawPath::Mesh,
        .task = "sphere_ms",
        .mesh = "sphere_ms",
        .meshLod = DrawPath::Tessellation,
        .topology = Topology::Quad4,
        .partitioning = Partitioning::Integer,
        .culls = true,
    };
    return kInfo;
  }
  std::vector<uint32_t> meshTable() const override { return stripTable(); }
};

}  // namespace

const Scheme& sphereMsScheme() {
  static const SphereMs scheme;
  return scheme;
}

}  // namespace lb
