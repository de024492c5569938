// An out-of-tree scheme (docs/plugins.md): lodbench's sphere rule (schemes/sphere.cpp) under a new
// name, built against the installed package. NVIDIA, "DirectX 11 Terrain Tessellation" (Cantlay
// 2011): "Hull Shader: Tessellation LOD" and "Crack-Free Tessellation". Shader: shaders/own_sphere.tesc.
#include "schemes/plugin_api.h"
#include "shaders/own_sphere_params.h"

namespace {

class OwnSphere : public lb::Scheme {
 public:
  const lb::SchemeInfo& info() const override {
    static const lb::SchemeInfo kInfo = {
        .name = "own-sphere",
        .description = "sphere's rule as a plugin: projected edge sphere / target triangle width",
        .seed = "nvidia-dx11-terrain-tessellation-2011: Hull Shader: Tessellation LOD; Crack-Free Tessellation",
        .params = {{"tri_size", LB_OWN_SPHERE_TRI_SIZE, 3, 0.5, 64, false, "target triangle width in pixels"},
                   {lb::kIntegerParam, LB_OWN_SPHERE_INTEGER, 0, 0, 1, true,
                    "1 = integer partitioning instead of fractional_even"}},
        .mainParam = "tri_size",
        .mainParamRole = lb::MainParamRole::TriangleWidthPx,
        .front = {2, 4, 8},
        .topology = lb::Topology::Quad4,
        .partitioning = lb::Partitioning::FractionalEven,
        .tesc = "own_sphere",
        .tese = "terrain_quad",
        .culls = true,
    };
    return kInfo;
  }
};

void addSchemes(lb::PluginSchemes& out) {
  out.push_back(std::make_unique<OwnSphere>());
}

}  // namespace

LODBENCH_PLUGIN("own-scheme", addSchemes)
