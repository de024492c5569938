// Rapp 2011 (bachelor thesis), 5.2.4 "Shader Pipeline", Figures 5-11 and 5-13, with Phong tessellation
// after Boubekeur & Alexa 2008. Triangle patches (two per grid quad); the control shader culls
// triangles outside the frustum or facing away (each with a tolerance), sets edge factors from the
// edge's length on screen / desired triangle size, and multiplies them by the density map of 5.2.3
// (schemes/preprocess/density_map.cpp); the evaluation shader (terrain_tri.tese) places vertices on the
// Phong surface with shape factor alpha. fractional_odd, as in Figure 5-11.
// Shader: shaders/phong.tesc.
//
// Scale-free as it stands: tri_size is in pixels, the frustum tolerance in longest triangle edges,
// the back-face tolerance a cosine, alpha unitless and the density map's threshold and scale work
// on range-normalised heights per sample (tests/test_scale.cpp checks it).
#include "render/scheme.h"
#include "schemes/preprocess/density_map.h"
#include "shaders/phong_params.h"
#include "terrain/heightfield.h"

namespace lb {
namespace {

class Phong : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "phong",
        .description = "triangles: screen-space edge length / tri size x density, culling, Phong tessellation",
        .seed = "rapp-adaptive-terrain-thesis-2011: 5.2.4 (Figures 5-11, 5-13); Boubekeur & Alexa 2008",
        .params =
            {
                {"tri_size", LB_PHONG_TRI_SIZE, 4, 0.5, 64, false,
                 "desired triangle edge on screen in pixels (the thesis measured 4)"},
                // Boubekeur & Alexa recommend 3/4; the thesis shows cracks near the horizon at 0.75.
                {"alpha", LB_PHONG_ALPHA, 0.75, 0, 1, false,
                 "Phong shape factor: 0 flat triangles, 1 full Phong surface"},
                // alpha bounds how far Phong moves a point (in longest edges), but that bound is loose: on the
                // shipped paths 0 and 4 give identical images at alpha 1, while 1 keeps 7x the triangles at low
                // altitude.
                {"frustum_tolerance", LB_PHONG_FRUSTUM_TOLERANCE, 0.1, 0, 4, false,
                 "frustum cull margin in longest triangle edges (>= alpha can never cull a visible triangle)"},
                {"backface_tolerance", LB_PHONG_BACKFACE_TOLERANCE, 0.25, 0, 1, false,
                 "cull when every edge normal . direction to eye <= -this (1: never cull)"},
                {"threshold", LB_PHONG_THRESHOLD, 0, 0, 1, false,
                 "density map: second differences below this are ignored"},
                {"scale", LB_PHONG_SCALE, 40, 0, 10000, false,
                 "density map: density = scale * weighted second differences"},
            },
        .mainParam = "tri_size",
        .mainParamRole = MainParamRole::TriangleWidthPx,
        .front = {2, 4, 8},
        .topology = Topology::Tri3,
        .partitioning = Partitioning::FractionalOdd,
        .tesc = "phong",
        .tese = "terrain_tri",
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

const Scheme& phongScheme() {
  static const Phong scheme;
  return scheme;
}

}  // namespace lb
