// practical-d3d11-ch9 "Dynamic Tessellation", 9.1.2 "Pre-Processing the Height Map", Listings
// 9.10-9.16: a compute pass reduces each 16x16 heightmap block to a plane normal and the standard
// deviation of the samples' distances to it; the control shader weights the distance LOD of
// Listing 9.7 by that coplanarity. fractional_odd as in the book. fit = 0 is the book's plane
// (corner normals, lowest corner, inconsistent x/z scales, uncentred RMS); fit = 1 a least-squares
// plane in world units with a centred deviation. Shaders: planefit.comp, planefit.tesc; CPU
// reference: harness/terrain/plane_fit.cpp.
#include <algorithm>
#include <sstream>
#include <string>

#include "error.h"
#include "render/scheme.h"
#include "shaders/planefit_params.h"
#include "terrain/heightfield.h"
#include "terrain/plane_fit.h"

namespace lb {
namespace {

class PlaneFitScheme : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        "planefit",
        "distance LOD weighted by per-16x16-block coplanarity from a compute pre-pass",
        "practical-d3d11-ch9: 9.1.2 Pre-Processing the Height Map, Listings 9.10-9.16 (+ Listing 9.7)",
        // Order matters: the shaders read parameters by index (distance_lod.glsl: 0-3, planefit.comp: 4,
        // planefit.tesc: 5).
        {{"min_lod", LB_PLANEFIT_MIN_LOD, 1, 1, 64, false, "level of flat or distant patches (minMaxLOD.x)"},
         {"max_lod", LB_PLANEFIT_MAX_LOD, 32, 1, 64, false, "level of rough patches at dmin and nearer (minMaxLOD.y)"},
         {"dmin", LB_PLANEFIT_DMIN, 50, 0, 1e6, false, "world distance of full distance LOD (minMaxDistance.x)"},
         {"dmax", LB_PLANEFIT_DMAX, 1000, 0, 1e6, false, "world distance where the LOD reaches min_lod (minMaxDistance.y)"},
         {"fit", LB_PLANEFIT_FIT, 0, 0, 1, true, "fit=book|lsq: 0 = the book's corner-normal plane, 1 = least-squares plane"},
         // The book's deviation is mostly the tilt of its nearly vertical plane (0.3-0.8 on the
         // procedural terrains); the least-squares one is in world units (a few units there).
         {"roughness", LB_PLANEFIT_ROUGHNESS, 0.75, 1e-6, 1e6, false,
          "block deviation earning the full distance LOD, in the fit's units (book: ~0.3-0.8; lsq: world units, e.g. "
          "4)"}},
        Topology::Quad4,
        Partitioning::FractionalOdd,
        "planefit",
        "terrain_quad",
        true,
        "planefit",
    };
    return kInfo;
  }
  float maxLevel(const ParamValues& v) const override { return float(std::max(v.at("min_lod"), v.at("max_lod"))); }
  TextureSize computeOutputSize(const Heightfield& hf) const override {
    return {planeFitBlockCount(hf.width), planeFitBlockCount(hf.height)};
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
