// NVIDIA, "DirectX 11 Terrain Tessellation" (Cantlay 2011), "Hull Shader: Tessellation LOD", the
// edge-projection alternative the sample keeps commented out (Figure 7): edge factor = screen
// length of the displaced patch edge / target triangle width. It fails edge-on, which is why the
// sample projects spheres instead; the scenario library (configs/scenarios/edge-on-ridge.json)
// provokes that failure. Its own scheme rather than a `sphere` parameter: it is a different LOD
// rule with its own row in every table, and `sphere` stays exactly the method the seed recommends.
// Shader: shaders/sphere_edge.tesc.
#include "render/scheme.h"
#include "shaders/sphere_edge_params.h"

namespace lb {
namespace {

class SphereEdge : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "sphere-edge",
        .description = "screen-space projected patch edge / target triangle width (fails edge-on)",
        .seed =
            "nvidia-dx11-terrain-tessellation-2011: Hull Shader: Tessellation LOD (Figure 7, commented-out edge "
            "version)",
        .params = {{"tri_size", LB_SPHERE_EDGE_TRI_SIZE, 3, 0.5, 64, false, "target triangle width in pixels"},
                   {kIntegerParam, LB_SPHERE_EDGE_INTEGER, 0, 0, 1, true,
                    "1 = integer partitioning instead of fractional_even"}},
        .mainParam = "tri_size",
        .mainParamRole = MainParamRole::TriangleWidthPx,
        .front = {2, 4, 8},
        .topology = Topology::Quad4,
        .partitioning = Partitioning::FractionalEven,
        .tesc = "sphere_edge",
        .tese = "terrain_quad",
        .culls = true,
    };
    return kInfo;
  }
};

}  // namespace

const Scheme& sphereEdgeScheme() {
  static const SphereEdge scheme;
  return scheme;
}

}  // namespace lb
