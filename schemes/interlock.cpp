// Practical Rendering & Computation with Direct3D 11, ch. 9.1.1 "GPU-Accelerated Interlocking
// Tiles Algorithm" (after Snook 2001), Listings 9.1, 9.2, 9.4-9.7: 12-control-point patches (own
// corners + two points of each neighbour, clamped at the terrain border); the LODs of the patch's
// midpoint and its four neighbours' midpoints, linear in distance between min/max distance and
// min/max LOD; inner = own LOD, edge = min(own, neighbour); fractional_odd. Shader:
// shaders/interlock.tesc. Frustum culling is our addition (cull=1, as the sphere scheme does).
#include <algorithm>

#include "render/scheme.h"
#include "shaders/interlock_params.h"

namespace lb {
namespace {

class Interlock : public Scheme {
 public:
  const SchemeInfo& info() const override {
    // Listing 9.7's minMaxDistance / minMaxLOD. The book gives no values. Distances are fractions
    // of the terrain extent (scale-free: the same picture at any world scale gets the same
    // levels; the extent, not the patch size, because Listing 9.7 compares with two
    // application-wide distances). The defaults keep the earlier world-unit ones chosen on the
    // 1000-unit procedural terrain in proportion: dmin 100 -> 0.1, dmax 1500 -> 1.5 (LOD falls to
    // 1 about a terrain diagonal away). max_lod 16 is one segment per heightfield texel for 513
    // samples over a 32-patch grid (the book sizes its height map 4-8x its grid for this reason).
    static const SchemeInfo kInfo = {
        .name = "interlock",
        .description = "interlocking tiles: distance LOD of own + 4 neighbour midpoints, edge = min",
        .seed = "practical-d3d11-ch9: 9.1.1 GPU-Accelerated Interlocking Tiles, Listings 9.1, 9.2, 9.4-9.7",
        .params = {{"dmin", LB_INTERLOCK_DMIN, 0.1, 0, 8, false,
                    "distance / terrain extent at and below which a midpoint gets max_lod"},
                   {"dmax", LB_INTERLOCK_DMAX, 1.5, 0, 8, false,
                    "distance / terrain extent at and beyond which a midpoint gets min_lod"},
                   {"min_lod", LB_INTERLOCK_MIN_LOD, 1, 1, 64, false, "level of distant patches (minMaxLOD.x)"},
                   {"max_lod", LB_INTERLOCK_MAX_LOD, 16, 1, 64, false, "level of near patches (minMaxLOD.y)"},
                   {"cull", LB_INTERLOCK_CULL, 1, 0, 1, true,
                    "1: per-patch frustum culling (not in the book); 0: draw every patch"}},
        .mainParam = "max_lod",
        .front = {4, 8, 16},
        .topology = Topology::Quad12,
        .partitioning = Partitioning::FractionalOdd,
        .tesc = "interlock",
        .tese = "terrain_quad",
        .culls = true,
    };
    return kInfo;
  }
  float maxLevel(const ParamValues& v) const override { return float(std::max(v.at("min_lod"), v.at("max_lod"))); }
};

}  // namespace

const Scheme& interlockScheme() {
  static const Interlock scheme;
  return scheme;
}

}  // namespace lb
