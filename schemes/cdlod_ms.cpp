// cdlod-ms: cdlod (schemes/cdlod.cpp: Strugar 2010, LODSelect and the morph vertex shader) drawn by
// task and mesh shaders instead of instancing its grid mesh, so cdlod against cdlod-ms is instancing
// against mesh shading at one LOD decision. The selection is cdlod's own object (its parameters,
// node sizes, ranges and morph constants), its records the instance records the instanced path
// would draw; the task shader (shaders/cdlod_ms.task) reads one selected quadrant an invocation and
// the mesh shader (shaders/cdlod_ms.mesh) emits its grid in blocks of at most 16 x 8 cells, each
// vertex placed and morphed by cdlod's vertex function (shaders/cdlod_vertex.glsl), each cell cut
// along the footprint's diagonal: the same triangles, the same points. cdlod's seam check
// (cdlod_seam_risk) counts the selection both draw; it stays cdlod's (a counter names one scheme).
// docs/draw-paths.md, "The mesh path".
#include "render/scheme.h"

namespace lb {

const Scheme& cdlodScheme();

namespace {

class CdlodMs : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = [] {
      const SchemeInfo& twin = cdlodScheme().info();
      return SchemeInfo{
          .name = "cdlod-ms",
          .description = "cdlod's CPU quadtree selection and morph, each quadrant's grid emitted by mesh shaders",
          .seed =
              "Strugar 2010, Continuous Distance-Dependent Level of Detail (LODSelect, morph), amplified by "
              "task and mesh shaders (VK_EXT_mesh_shader)",
          .params = twin.params,
          .mainParam = twin.mainParam,
          .mainParamRole = twin.mainParamRole,
          .front = twin.front,
          .path = DrawPath::Mesh,
          .task = "cdlod_ms",
          .mesh = "cdlod_ms",
          .meshLod = DrawPath::InstancedGrid,
      };
    }();
    return kInfo;
  }
  void validate(const ParamValues& v) const override { cdlodScheme().validate(v); }
  double targetAreaPx(const ParamValues& v) const override { return cdlodScheme().targetAreaPx(v); }
  std::unique_ptr<InstancedLod> instancedLod(const Heightfield& hf, const ParamValues& v) const override {
    return cdlodScheme().instancedLod(hf, v);
  }
};

}  // namespace

const Scheme& cdlodMsScheme() {
  static const CdlodMs scheme;
  return scheme;
}

}  // namespace lb
