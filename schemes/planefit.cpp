// practical-d3d11-ch9 "Dynamic Tessellation", 9.1.2 "Pre-Processing the Height Map", Listings
// 9.10-9.16: a compute pass reduces each 16x16 heightmap block to a plane normal and the standard
// deviation of the samples' distances to it; the control shader weights the distance LOD of
// Listing 9.7 by that coplanarity. fractional_odd as in the book. fit = 0 is the book's plane
// (corner normals, lowest corner, inconsistent x/z scales, uncentred RMS); fit = 1 a least-squares
// plane in world units with a centred deviation. Shaders: planefit.comp, planefit.tesc; CPU
// reference: schemes/preprocess/plane_fit.cpp.
//
// Scale-free (the same picture at any world scale gets the same levels): dmin and dmax are
// fractions of the terrain extent, as in the distance scheme (defaults 50 -> 0.05 and 1000 -> 1.0
// of the 1000-unit terrain they were chosen on; the book prints no values). `roughness` is in the
// fit's own units made scale-free: fit = 0 reads the book's deviation, which is already unitless
// (heights normalised to the height range as the book's UNORM texture holds them, x and z in block
// units); fit = 1's least-squares deviation is in world units, so the shader compares it with
// roughness x extent. The extent, not the height range: the deviation matters through its
// projected size, deviation / viewing distance, and viewing distances scale with the extent (the
// paths and dmin/dmax are in extents); relative to the height range, doubling height_scale would
// leave the weights unchanged although every deviation on screen doubles. The former lsq example
// of 4 world units on the 1000-unit terrain is 0.004.
#include <algorithm>
#include <sstream>
#include <string>

#include "error.h"
#include "render/scheme.h"
#include "schemes/preprocess/plane_fit.h"
#include "shaders/planefit_params.h"
#include "terrain/heightfield.h"

namespace lb {
namespace {

class PlaneFitScheme : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "planefit",
        .description = "distance LOD weighted by per-16x16-block coplanarity from a compute pre-pass",
        .seed = "practical-d3d11-ch9: 9.1.2 Pre-Processing the Height Map, Listings 9.10-9.16 (+ Listing 9.7)",
        .params =
            {{"min_lod", LB_PLANEFIT_MIN_LOD, 1, 1, 64, false, "level of flat or distant patches (minMaxLOD.x)"},
             {"max_lod", LB_PLANEFIT_MAX_LOD, 32, 1, 64, false,
              "level of rough patches at dmin and nearer (minMaxLOD.y)"},
             {"dmin", LB_PLANEFIT_DMIN, 0.05, 0, 8, false,
              "distance / terrain extent of full distance LOD (minMaxDistance.x)"},
             {"dmax", LB_PLANEFIT_DMAX, 1.0, 0, 8, false,
              "distance / terrain extent where the LOD reaches min_lod (minMaxDistance.y)"},
             {"fit", LB_PLANEFIT_FIT, 0, 0, 1, true,
              "fit=book|lsq: 0 = the book's corner-normal plane, 1 = least-squares plane"},
             // The book's deviation is mostly the tilt of its nearly vertical plane (0.3-0.8 on the
             // procedural terrains); the least-squares one, divided by the extent, is ~0.001-0.02 there.
             {"roughness", LB_PLANEFIT_ROUGHNESS, 0.75, 1e-6, 1e6, false,
              "block deviation earning the full distance LOD (fit=0: the book's unitless deviation, ~0.3-0.8; fit=1: "
              "fraction of the terrain extent, e.g. 0.004)"}},
        .mainParam = "max_lod",
        .front = {8, 16, 32},
        .topology = Topology::Quad4,
        .partitioning = Partitioning::FractionalOdd,
        .tesc = "planefit",
        .tese = "terrain_quad",
        .culls = true,
        .compute = "planefit",
    };
    return kInfo;
  }
  float maxLevel(const ParamValues& v) const override { return float(std::max(v.at("min_lod"), v.at("max_lod"))); }
  TextureSize computeOutputSize(const Heightfield& hf) const override {
    return {planeFitBlockCount(hf.width), planeFitBlockCount(hf.height)};
  }
  // The blocks as planefit.comp's texels: normal x, y, z and deviation.
  SchemeTexture computeReference(const Heightfield& hf, const ParamValues& v) const override {
    PlaneFitResult r = fitPlanes(hf, v.at("fit") != 0 ? PlaneFit::LeastSquares : PlaneFit::Book);
    SchemeTexture tex{r.width, r.height, {}};
    tex.rgba.reserve(r.blocks.size() * 4);
    for (const PlaneFitBlock& b : r.blocks)
      tex.rgba.insert(tex.rgba.end(), {b.normal.x, b.normal.y, b.normal.z, b.deviation});
    return tex;
  }
  void validate(const ParamValues& v) const override {
    requireOrdered(info().name, v, "dmin", "dmax", true);
    requireOrdered(info().name, v, "min_lod", "max_lod", false);
  }
};

}  // namespace

const Scheme& planeFitScheme() {
  static const PlaneFitScheme scheme;
  return scheme;
}

}  // namespace lb
