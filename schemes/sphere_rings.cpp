// NVIDIA, "DirectX 11 Terrain Tessellation" (Cantlay 2011): "Non-Uniform Patch Sizes" through
// "Advisability of Adjacent, Different-sized Patches" (TileRing, AssignNeighbourSizes), with the
// LOD of "Hull Shader: Tessellation LOD". Concentric square rings of tiles, each ring's tiles twice
// the size of the inner ring's, 8x8 patches per tile; per-tile adjacency scalars; the control
// shader (shaders/sphere_rings.tesc) reconciles levels across ring boundaries.
//
// Layout: fixed, centred on the terrain's centre and built once at setScheme. The sample re-centres
// the rings on the camera every frame; a fixed layout keeps the base mesh, culling bounds and
// counters identical for any path, needs no per-frame renderer hook, and still shows every
// boundary effect (cameras far from the centre see coarse rings near them: a known limitation).
// Patches entirely outside the terrain are dropped; those overlapping its border sample the
// clamped heightfield, as terrainHeight() does. The sample uses 16x16-tile rings; 8x8 keeps the
// patch count lavapipe-sized (4096 + 3072 per further ring) with the same boundary structure.
// Corners lie on a lattice of extent / 2^k when tile_size is 0 or 1/2^n, so for round extents
// (1000) the shader's reconstruction p0 + (p0 - p1) of a larger neighbour's corner is bit-exact;
// otherwise it can be an ulp off, the seed's first caveat under "Advisability".
#include <cmath>
#include <map>
#include <utility>

#include "error.h"
#include "metrics/cracks.h"
#include "render/patch_grid.h"
#include "render/scheme.h"
#include "shaders/sphere_rings_params.h"
#include "terrain/heightfield.h"

namespace lb {
namespace {

constexpr int kPatchesPerTile = 8;  // seed: 8x8 patches per tile
constexpr int kRingTiles = 8;       // tiles across a ring; rings after the first have a 4x4-tile hole
constexpr int kHoleLo = kRingTiles / 4, kHoleHi = kRingTiles * 3 / 4;
constexpr int kFloatsPerPatch = 8;  // adjacency -x, -z, +x, +z; patch x, z in tile; ring; patch size

bool inHole(int ring, int tx, int tz) {
  return ring > 0 && tx >= kHoleLo && tx < kHoleHi && tz >= kHoleLo && tz < kHoleHi;
}

// AssignNeighbourSizes: the neighbour tile's size relative to ours across one side of tile (tx, tz).
float neighbourSize(int ring, int rings, int tx, int tz) {
  bool outside = tx < 0 || tz < 0 || tx >= kRingTiles || tz >= kRingTiles;
  if (outside) return ring + 1 < rings ? 2.0f : 1.0f;  // the outermost ring has no neighbour
  return inHole(ring, tx, tz) ? 0.5f : 1.0f;
}

class SphereRings : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        "sphere-rings",
        "sphere LOD on concentric tile rings doubling in size, crack-free across ring boundaries",
        "nvidia-dx11-terrain-tessellation-2011: Non-Uniform Patch Sizes; Implementation - Adjacency of "
        "Different-Sized Patches; Advisability of Adjacent, Different-sized Patches",
        {{"tri_size", LB_SPHERE_RINGS_TRI_SIZE, 3, 0.5, 64, false, "target triangle width in pixels (g_tessellatedTriSize)"},
         {"rings", LB_SPHERE_RINGS_RINGS, 4, 1, 8, true, "number of tile rings (8x8 tiles each, inner 4x4 hole after the first)"},
         {"tile_size", LB_SPHERE_RINGS_TILE_SIZE, 0, 0, 1, false, "innermost tile size / extent; 0 = the outer ring just covers the terrain"},
         {"pow2", LB_SPHERE_RINGS_POW2, 1, 0, 1, true, "1: power-of-2 levels at ring boundaries; 0: integer+even only (cracks)"}},
        Topology::Quad4,
        Partitioning::FractionalEven,
        "sphere_rings",
        "terrain_quad",
        true,
    };
    return kInfo;
  }

  PatchGeometry patchGeometry(const Heightfield& hf, const ParamValues& v) const override {
    const int rings = int(v.at("rings"));
    // Fit: ring r spans kRingTiles * tile * 2^r; the outermost one spans the extent.
    double tile0 =
        v.at("tile_size") > 0 ? v.at("tile_size") * hf.extent : hf.extent / (kRingTiles * std::ldexp(1.0, rings - 1));
    if (tile0 < hf.extent / 4096.0) throw InputError("sphere-rings: tile_size must be 0 (fit) or >= 1/4096");
    // Corners on a lattice of the finest patch size, centred on the terrain: shared corners get
    // one vertex, so neighbours see bit-identical end points.
    const double unit = tile0 / kPatchesPerTile, centre = 0.5 * hf.extent;
    PatchGeometry g;
    std::map<std::pair<long, long>, uint32_t> vertexOf;
    auto vertex = [&](long ix, long iz) {
      auto [it, added] = vertexOf.try_emplace({ix, iz}, uint32_t(g.vertices.size()));
      if (added) g.vertices.emplace_back(float(centre + ix * unit), float(centre + iz * unit));
      return it->second;
    };
    for (int r = 0; r < rings; ++r) {
      const long step = 1L << r;  // patch size in lattice units
      const long origin = -long(kRingTiles / 2 * kPatchesPerTile) * step;
      for (int tz = 0; tz < kRingTiles; ++tz)
        for (int tx = 0; tx < kRingTiles; ++tx) {
          if (inHole(r, tx, tz)) continue;
          float adj[4] = {neighbourSize(r, rings, tx - 1, tz), neighbourSize(r, rings, tx, tz - 1),
                          neighbourSize(r, rings, tx + 1, tz), neighbourSize(r, rings, tx, tz + 1)};
          for (int pz = 0; pz < kPatchesPerTile; ++pz)
            for (int px = 0; px < kPatchesPerTile; ++px) {
              long ix = origin + (tx * kPatchesPerTile + px) * step, iz = origin + (tz * kPatchesPerTile + pz) * step;
              glm::vec2 lo(float(centre + ix * unit), float(centre + iz * unit));
              glm::vec2 hi(float(centre + (ix + step) * unit), float(centre + (iz + step) * unit));
              if (hi.x <= 0 || hi.y <= 0 || lo.x >= hf.extent || lo.y >= hf.extent) continue;
              g.indices.insert(g.indices.end(), {vertex(ix, iz), vertex(ix + step, iz), vertex(ix + step, iz + step),
                                                 vertex(ix, iz + step)});
              g.bounds.push_back(rectHeightBounds(hf, lo, hi));
              g.schemeBuffer.insert(g.schemeBuffer.end(), {adj[0], adj[1], adj[2], adj[3], float(px), float(pz),
                                                           float(r), float(step * unit)});
            }
        }
    }
    static_assert(kFloatsPerPatch == 8, "matches RingPatch in shaders/sphere_rings.tesc");
    return g;
  }

  // Ring boundaries are T-junctions: the grid rule does not apply; compare vertex patterns.
  long crackEdges(const Heightfield& hf, const ParamValues& v, const std::vector<float>& levels) const override {
    return layoutCrackEdges(patchGeometry(hf, v), levels);
  }
};

}  // namespace

const Scheme& sphereRingsScheme() {
  static const SphereRings scheme;
  return scheme;
}

}  // namespace lb
