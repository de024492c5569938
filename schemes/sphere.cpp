// NVIDIA, "DirectX 11 Terrain Tessellation" (Cantlay 2011): "Hull Shader: Tessellation LOD" and
// "Crack-Free Tessellation". Uniform patch size; per edge, the screen-space diameter of a sphere
// around the displaced edge divided by the target triangle width; per-patch frustum culling;
// fractional_even partitioning. Shader: shaders/sphere.tesc.
#include "render/scheme.h"
#include "shaders/sphere_params.h"

namespace lb {
namespace {

class Sphere : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "sphere",
        .description = "screen-space projected edge sphere / target triangle width",
        .seed = "nvidia-dx11-terrain-tessellation-2011: Hull Shader: Tessellation LOD; Crack-Free Tessellation",
        .params = {{"tri_size", LB_SPHERE_TRI_SIZE, 3, 0.5, 64, false,
                    "target triangle width in pixels (g_tessellatedTriSize)"},
                   {kIntegerParam, LB_SPHERE_INTEGER, 0, 0, 1, true,
                    "1 = integer partitioning instead of fractional_even (popping scenario)"}},
        .mainParam = "tri_size",
        .mainParamRole = MainParamRole::TriangleWidthPx,
        .front = {2, 4, 8},
        .topology = Topology::Quad4,
        .partitioning = Partitioning::FractionalEven,
        .tesc = "sphere",
        .tese = "terrain_quad",
        .culls = true,
    };
    return kInfo;
  }
};

}  // namespace

const Scheme& sphereScheme() {
  static const Sphere scheme;
  return scheme;
}

}  // namespace lb
