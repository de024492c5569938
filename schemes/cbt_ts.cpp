// cbt-ts: cbt's tree, update and rule unchanged (schemes/cbt.cpp), each leaf drawn as one triangle
// patch tessellated at level n = 2^subd on every edge, integer spacing, as LEB2D's TS pipeline does.
// With the LOD decision held fixed, cbt against cbt-ts is the cost of amplifying in the tessellator
// against instancing a mesh. The tessellator cuts a triangle in concentric rings, not in cbt's 4^s
// grid: T(n) = 6 (n - 1) + T(n - 2) triangles (T(1) = 1, T(0) = 0; 96 at n = 8 against cbt's 64),
// with the same n + 1 vertices on every edge, so neighbouring leaves still share their edges'
// vertices exactly (shaders/cbt_ts.tese). The leaves go out in draws of at most
// kMaxVerticesPerDraw / (n + 1)^2 patches (render/draw_limits.h: lavapipe's limit on tessellated
// vertices a draw; (n + 1)^2 bounds the ring layout's vertices), written by the batch pass and drawn
// with one vkCmdDrawIndexedIndirectCount, on every device alike.
#include "render/draw_limits.h"
#include "schemes/cbt.h"
#include "shaders/cbt_params.h"

namespace lb {
namespace {

class CbtTs : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "cbt-ts",
        .description = "cbt's tree and update, each leaf a triangle patch tessellated at level 2^subd",
        .seed = "Dupuy 2020 / LEB2D's TS pipeline (the same tree drawn through the tessellator)",
        .params = cbtParams(),
        .mainParam = "tri_size",
        .mainParamRole = MainParamRole::TriangleWidthPx,
        .front = {4, 7, 14},
        .path = DrawPath::GpuIndirect,
        .vert = "cbt_ts",
        .topology = Topology::Tri3,
        .partitioning = Partitioning::Integer,
        .tesc = "cbt_ts",
        .tese = "cbt_ts",
    };
    return kInfo;
  }
  double targetAreaPx(const ParamValues& v) const override { return cbtTargetAreaPx(v); }
  GpuLod gpuLod(const Heightfield& hf, const ParamValues& v, const GpuLodBudget& budget) const override {
    const uint32_t n = 1u << uint32_t(v.at("subd"));
    GpuLod g = cbtTree(hf, v, budget, kMaxVerticesPerDraw / ((n + 1) * (n + 1)));
    // One patch a leaf: control points a, b, c picked by the vertex shader from the record.
    g.footprint = {"patch", {{1.0f, 0.0f}, {0.0f, 0.0f}, {0.0f, 1.0f}}, {0, 1, 2}};
    g.initialState[LB_CBT_INDEX_COUNT] = 3;
    uint32_t rings = n % 2;  // T(n), ring by ring from the centre
    for (uint32_t k = 2 - n % 2; k <= n; k += 2) rings += 6 * (k - 1);
    g.trianglesPerInstance = rings;
    return g;
  }
};

}  // namespace

const Scheme& cbtTsScheme() {
  static const CbtTs scheme;
  return scheme;
}

}  // namespace lb
