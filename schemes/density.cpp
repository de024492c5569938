// AMD "Detail Tessellation 11" (Thibieroz), "Density-based Tessellation", and Rapp 2011 (bachelor
// thesis), 5.2.3 "Density Map Creation": a density map from the heightfield's second-order height
// variation is built at load time (schemes/preprocess/density_map.cpp); per edge, the maximum density
// along the edge multiplies a screen-space factor. The screen-space term is NVIDIA's projected edge
// sphere (sphere scheme); fractional_even as in that scheme, so the two differ only by the density.
// Shader: shaders/density.tesc.
//
// Scale-free as it stands: `threshold` and the second differences are in heights normalised to the
// terrain's height range, taken per heightfield sample (no world distance), and tri_size is in
// pixels, so scaling extent, heights and camera together changes nothing (tests/test_scale.cpp).
#include "render/scheme.h"
#include "schemes/preprocess/density_map.h"
#include "shaders/density_params.h"
#include "terrain/heightfield.h"

namespace lb {
namespace {

class Density : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "density",
        .description = "screen-space edge sphere / tri size, times the maximum height-curvature density along the edge",
        .seed = "amd-detail-tessellation-11: Density-based Tessellation; rapp-adaptive-terrain-thesis-2011: 5.2.3",
        .params =
            {
                // Heights are normalised to [0,1]; the SDK used 2/255 to skip its 8-bit steps, float maps have none.
                {"threshold", LB_DENSITY_THRESHOLD, 0, 0, 1, false,
                 "second differences below this (normalised height) are ignored"},
                // Per-sample second differences shrink with resolution: 40 spreads a 513^2 map over (1/255, 1].
                {"scale", LB_DENSITY_SCALE, 40, 0, 10000, false,
                 "density = scale * weighted second differences, clamped to [1/255, 1]"},
                {"tri_size", LB_DENSITY_TRI_SIZE, 3, 0.5, 64, false,
                 "target triangle width in pixels before the density factor"},
            },
        .mainParam = "tri_size",
        .mainParamRole = MainParamRole::TriangleWidthPx,
        .front = {2, 4, 8},
        .topology = Topology::Quad4,
        .partitioning = Partitioning::FractionalEven,
        .tesc = "density",
        .tese = "terrain_quad",
        .culls = true,
    };
    return kInfo;
  }

  SampleMap sampleMap(const Heightfield& hf, const ParamValues& v) const override {
    const float threshold = float(v.at("threshold")), scale = float(v.at("scale"));
    return {[&hf, threshold, scale](int z, int x0, int count, float* out) {
      densityRow(hf, threshold, scale, z, x0, count, out);
    }};
  }
};

}  // namespace

const Scheme& densityScheme() {
  static const Density scheme;
  return scheme;
}

}  // namespace lb
