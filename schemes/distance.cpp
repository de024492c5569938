// practical-d3d11-ch9 "Dynamic Tessellation", 9.1.1 Listing 9.7 (ComputePatchLOD) with the patch
// midpoint of Listing 9.6; amd-detail-tessellation-11 "Distance-adaptive Tessellation" for the
// per-edge factors that keep neighbours crack-free. fractional_odd as in the book (section 9.1.1).
// Shaders: shaders/distance.tesc, shaders/distance_lod.glsl.
//
// Scale-free: dmin and dmax (the book's minMaxDistance) are fractions of the terrain extent, so
// the same picture (terrain, heights and camera scaled together) gets the same levels at any world
// scale. The book prints no values; the defaults keep this scheme's earlier world-unit ones in
// proportion to the 1000-unit procedural terrain they were chosen on: dmin 50 -> 0.05, dmax 1000
// -> 1.0 (full detail within a twentieth of the terrain, min_lod from one terrain width away). The
// extent is the seed's natural unit: ComputeScaledDistance compares the camera distance with two
// application-wide distances, not with anything per patch, so tying them to the patch size would
// make `grid` change the LOD falloff.
#include <algorithm>
#include <sstream>
#include <string>

#include "error.h"
#include "render/scheme.h"
#include "shaders/distance_params.h"

namespace lb {
namespace {

class Distance : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "distance",
        .description =
            "lerp(min_lod, max_lod) by the camera distance of patch and edge midpoints between dmin and dmax",
        .seed =
            "practical-d3d11-ch9: 9.1.1 Listing 9.7 ComputePatchLOD; amd-detail-tessellation-11: Distance-adaptive "
            "Tessellation (per-edge factors)",
        .params = {{"min_lod", LB_DISTANCE_MIN_LOD, 1, 1, 64, false, "level at distance dmax and beyond (minMaxLOD.x)"},
                   {"max_lod", LB_DISTANCE_MAX_LOD, 32, 1, 64, false,
                    "level at distance dmin and nearer (minMaxLOD.y)"},
                   // Range up to 8 extents (twice the far plane): old world-unit values (50, 1000) fail loudly.
                   {"dmin", LB_DISTANCE_DMIN, 0.05, 0, 8, false,
                    "distance / terrain extent at which the level reaches max_lod (minMaxDistance.x)"},
                   {"dmax", LB_DISTANCE_DMAX, 1.0, 0, 8, false,
                    "distance / terrain extent at which the level falls to min_lod (minMaxDistance.y)"}},
        .mainParam = "max_lod",
        .front = {8, 16, 32},
        .topology = Topology::Quad4,
        .partitioning = Partitioning::FractionalOdd,
        .tesc = "distance",
        .tese = "terrain_quad",
        .culls = true,
    };
    return kInfo;
  }
  float maxLevel(const ParamValues& v) const override { return float(std::max(v.at("min_lod"), v.at("max_lod"))); }
  void validate(const ParamValues& v) const override {
    requireOrdered(info().name, v, "dmin", "dmax", true);
    requireOrdered(info().name, v, "min_lod", "max_lod", false);
  }
};

}  // namespace

const Scheme& distanceScheme() {
  static const Distance scheme;
  return scheme;
}

}  // namespace lb
