// Control between the baseline and the screen-space schemes: uniform's one fixed level with the
// per-patch frustum culling of NVIDIA's "DirectX 11 Terrain Tessellation" (Cantlay 2011), "Hull
// Shader: Tessellation LOD" (factor 0 outside the frustum). uniform -> uniform-cull is what culling
// alone saves, uniform-cull -> sphere what the level of detail saves. Shader: shaders/uniform_cull.tesc.
#include "render/scheme.h"
#include "shaders/uniform_params.h"

namespace lb {
namespace {

class UniformCull : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "uniform-cull",
        .description = "uniform's fixed level, patches outside the frustum culled (what culling alone saves)",
        .seed = "baseline + nvidia-dx11-terrain-tessellation-2011: Hull Shader: Tessellation LOD (frustum culling)",
        .params = {{"level", LB_UNIFORM_LEVEL, 8, 1, 64, true, "tessellation level of every edge and interior"}},
        .mainParam = "level",
        .front = {2, 4, 8},
        .topology = Topology::Quad4,
        .partitioning = Partitioning::Integer,
        .tesc = "uniform_cull",
        .culls = true,
    };
    return kInfo;
  }
  float maxLevel(const ParamValues& v) const override { return float(v.at("level")); }
};

}  // namespace

const Scheme& uniformCullScheme() {
  static const UniformCull scheme;
  return scheme;
}

}  // namespace lb
