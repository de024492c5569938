// cbt-ms: cbt's concurrent binary tree (schemes/cbt.cpp: Dupuy 2020; the LEB2D demo; Benyoub & Dupuy
// 2024), its update, rule, pool and passes unchanged, each leaf amplified by mesh shaders instead of
// an instanced leaf mesh, as LEB2D's MS pipeline does with the same tree; with cbt-ts, the same LOD
// drawn three ways. The task shader (shaders/cbt_ms.task) is dispatched from the indirect arguments
// the per-leaf passes use (one workgroup per 64 leaves, the state's LB_CBT_DISPATCH words), the mesh
// shader (shaders/cbt_ms.mesh) emits the leaves' 4^subd micro-triangles from the records cbt's
// records pass wrote, through cbt's vertex function (shaders/cbt_leaf.glsl): the same triangles,
// the same points. docs/draw-paths.md, "The mesh path".
#include "schemes/cbt.h"
#include "shaders/cbt_params.h"

namespace lb {
namespace {

class CbtMs : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "cbt-ms",
        .description = "cbt's tree and update, each leaf's micro-triangles emitted by mesh shaders",
        .seed =
            "Dupuy 2020 / LEB2D's MS pipeline (the same tree amplified by task and mesh shaders, VK_EXT_mesh_shader)",
        .params = cbtParams(),
        .mainParam = "tri_size",
        .mainParamRole = MainParamRole::TriangleWidthPx,
        .front = {4, 7, 14},
        .path = DrawPath::Mesh,
        .task = "cbt_ms",
        .mesh = "cbt_ms",
        .meshLod = DrawPath::GpuIndirect,
    };
    return kInfo;
  }
  double targetAreaPx(const ParamValues& v) const override { return cbtTargetAreaPx(v); }
  GpuLod gpuLod(const Heightfield& hf, const ParamValues& v, const GpuLodBudget& budget) const override {
    GpuLod g = cbtTree(hf, v, budget, 0);
    g.meshTasksWord = LB_CBT_DISPATCH;
    g.meshTaskRecords = LB_CBT_GROUP;
    return g;
  }
};

}  // namespace

const Scheme& cbtMsScheme() {
  static const CbtMs scheme;
  return scheme;
}

}  // namespace lb
