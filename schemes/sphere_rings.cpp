// NVIDIA, "DirectX 11 Terrain Tessellation" (Cantlay 2011): "Non-Uniform Patch Sizes" through
// "Advisability of Adjacent, Different-sized Patches" (TileRing, AssignNeighbourSizes), with the
// LOD of "Hull Shader: Tessellation LOD" and the snapping of "Scrolling in Displacement Map
// Generation". Concentric square rings of tiles, each ring's tiles twice the size of the inner
// ring's, 8x8 patches per tile; per-tile adjacency scalars; the control shader
// (shaders/sphere_rings.tesc) reconciles levels across ring boundaries.
//
// The rings follow the LOD camera. The patch mesh is built once, in ring-local lattice units (one
// unit = the innermost patch size, extent / grid, as every other scheme's patch): the ring lattice
// is translation-invariant, so every frame update() writes a centre K (lattice units) that the
// control shader adds to every corner. K is the LOD eye snapped to a multiple of the coarsest
// *patch* size 2^(R-1), as the sample snaps its displacement map ("only moves in multiples of the
// largest patch size"): every ring's corners then stay on that ring's fixed world lattice, so a
// moving camera never makes vertices swim, and the camera is within half a coarsest patch of the
// centre. (Snapping to the coarsest ring's *tile*, 8x coarser, would leave the camera up to half a
// coarsest tile off centre: outside the finest ring from 5 rings on.) K is clamped to the terrain,
// which the sample (an endless terrain) never needs: with `rings` at its default the outermost
// ring then always covers the whole terrain (32 * 2^(R-1) >= grid), even from a camera beyond it.
//
// Patches outside the terrain: the sample draws an endless terrain, we draw one tile. A patch no
// admissible centre brings over the terrain is never emitted; the others are culled per frame in
// the control shader (factor 0, like a patch outside the frustum), so no geometry is drawn beyond
// the terrain and the draw calls stay fixed (the seed's one draw per ring). Culling bounds come
// from a per-ring pyramid of exact patch height bounds on the world lattice (rectHeightBounds, as
// the uniform grid's), looked up at the patch's world lattice cell, so they move with the rings.
// A patch overlapping the border (grid not a multiple of 2^(R-1)) samples the clamped heightfield.
//
// Corners are integers (lattice units) until the shader maps them to world x = (v + K) * extent /
// grid, so the larger neighbour's corner the smaller patch reconstructs (p0 + (p0 - p1), Figure
// 12) is exact for any extent and grid: the seed's first caveat under "Advisability" cannot bite.
// The sample uses 16x16-tile rings; 8x8 keeps the patch count lavapipe-sized with the same
// boundary structure.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "error.h"
#include "render/patch_grid.h"
#include "render/scheme.h"
#include "schemes/sphere_rings_layout.h"
#include "shaders/shared.h"
#include "shaders/sphere_rings_params.h"
#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

namespace lb {

namespace {

constexpr int kPatchesPerTile = 8;  // seed: 8x8 patches per tile
constexpr int kRingTiles = 8;       // tiles across a ring; rings after the first have a 4x4-tile hole
constexpr int kHoleLo = kRingTiles / 4, kHoleHi = kRingTiles * 3 / 4;
constexpr long kRingHalf = kRingTiles * kPatchesPerTile / 2;  // ring 0's half-width in lattice units

bool inHole(int ring, int tx, int tz) {
  return ring > 0 && tx >= kHoleLo && tx < kHoleHi && tz >= kHoleLo && tz < kHoleHi;
}

// AssignNeighbourSizes: the neighbour tile's size relative to ours across one side of tile (tx, tz).
float neighbourSize(int ring, int rings, int tx, int tz) {
  bool outside = tx < 0 || tz < 0 || tx >= kRingTiles || tz >= kRingTiles;
  if (outside) return ring + 1 < rings ? 2.0f : 1.0f;  // the outermost ring has no neighbour
  return inHole(ring, tx, tz) ? 0.5f : 1.0f;
}

// The patch mesh; bounds pyramid only when asked (crack counting needs the topology alone).
PatchGeometry buildRings(const Heightfield& hf, const ParamValues& v, int grid, bool withBounds) {
  const int rings = ringCount(v, grid);
  const long coarsest = 1L << (rings - 1), maxCentre = long(grid) / coarsest * coarsest;
  PatchGeometry g;
  std::map<std::pair<long, long>, uint32_t> vertexOf;
  auto vertex = [&](long ix, long iz) {
    auto [it, added] = vertexOf.try_emplace({ix, iz}, uint32_t(g.vertices.size()));
    if (added) g.vertices.emplace_back(float(ix), float(iz));
    return it->second;
  };
  // Scheme buffer: header (level offsets, patch base), then RingPatch records, then the pyramid.
  std::vector<float> records;
  long patches = 0;
  for (int r = 0; r < rings; ++r) {
    const long step = 1L << r;  // patch size in lattice units
    const long origin = -kRingHalf * step;
    for (int tz = 0; tz < kRingTiles; ++tz)
      for (int tx = 0; tx < kRingTiles; ++tx) {
        if (inHole(r, tx, tz)) continue;
        float adj[4] = {neighbourSize(r, rings, tx - 1, tz), neighbourSize(r, rings, tx, tz - 1),
                        neighbourSize(r, rings, tx + 1, tz), neighbourSize(r, rings, tx, tz + 1)};
        for (int pz = 0; pz < kPatchesPerTile; ++pz)
          for (int px = 0; px < kPatchesPerTile; ++px) {
            long ix = origin + (tx * kPatchesPerTile + px) * step, iz = origin + (tz * kPatchesPerTile + pz) * step;
            // World span [ix + K, ix + step + K) for K in [0, maxCentre]: never over [0, grid)?
            auto never = [&](long i) { return i >= grid || i + step + maxCentre <= 0; };
            if (never(ix) || never(iz)) continue;
            g.indices.insert(g.indices.end(), {vertex(ix, iz), vertex(ix + step, iz), vertex(ix + step, iz + step),
                                               vertex(ix, iz + step)});
            records.insert(records.end(), {adj[0], adj[1], adj[2], adj[3], float(px), float(pz), float(r), 0.0f});
            ++patches;
          }
      }
  }
  static_assert(kRingFloatsPerPatch == 8, "matches RingPatch in shaders/sphere_rings.tesc");
  // Culling bounds per ring level on the world lattice; the renderer's own bounds are unused.
  g.bounds.assign(size_t(patches), glm::vec2(hf.minHeight, hf.maxHeight));
  // Offsets in vec2 units (the shader reads the buffer as vec2[]); every block has an even size.
  g.schemeBuffer.assign(kRingHeaderFloats, 0.0f);
  g.schemeBuffer[kRingMaxLevels] = float(kRingHeaderFloats / 2);
  g.schemeUnits = true;  // lattice units: worldPoint() in the control shader adds the terrain origin
  g.schemeBuffer.insert(g.schemeBuffer.end(), records.begin(), records.end());
  if (!withBounds) return g;
  // Ring 0's cells scan their samples (row bands on the terrain threads); every coarser level
  // takes the min and max of its 2 x 2 cells one level finer. A cell's samples are its children's:
  // their edges are the same floats (i * 2^r * unit in double, rounded once), so their texel
  // ranges meet or overlap, and a child past the lattice would only repeat the terrain's last
  // samples. The same bits as scanning every level (test_scheme_rings.cpp), and the terrain is
  // read once instead of once a ring (minutes single-threaded at 65537^2).
  const double unit = double(hf.extent) / grid;
  std::vector<std::vector<glm::vec2>> levels(static_cast<size_t>(rings));
  const long n0 = ringLatticeSize(grid, 0);
  levels[0].resize(size_t(n0 * n0));
  parallelRows(int(n0), [&](int j0, int j1) {
    for (long j = j0; j < j1; ++j)
      for (long i = 0; i < n0; ++i)
        levels[0][size_t(j * n0 + i)] = rectHeightBounds(hf, glm::vec2(float(i * unit), float(j * unit)),
                                                         glm::vec2(float((i + 1) * unit), float((j + 1) * unit)));
  });
  for (int r = 1; r < rings; ++r) {
    const long n = ringLatticeSize(grid, r), fine = ringLatticeSize(grid, r - 1);
    levels[size_t(r)].assign(size_t(n * n), glm::vec2(INFINITY, -INFINITY));
    for (long j = 0; j < fine; ++j)
      for (long i = 0; i < fine; ++i) {
        const glm::vec2 c = levels[size_t(r - 1)][size_t(j * fine + i)];
        glm::vec2& b = levels[size_t(r)][size_t((j / 2) * n + i / 2)];
        b = glm::vec2(std::min(b.x, c.x), std::max(b.y, c.y));
      }
  }
  for (int r = 0; r < rings; ++r) {
    g.schemeBuffer[size_t(r)] = float(g.schemeBuffer.size() / 2);
    for (const glm::vec2& b : levels[size_t(r)]) g.schemeBuffer.insert(g.schemeBuffer.end(), {b.x, b.y});
  }
  return g;
}

class SphereRings : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "sphere-rings",
        .description =
            "sphere LOD on concentric tile rings doubling in size around the LOD camera, crack-free across ring "
            "boundaries",
        .seed =
            "nvidia-dx11-terrain-tessellation-2011: Non-Uniform Patch Sizes; Implementation - Adjacency of "
            "Different-Sized Patches; Advisability of Adjacent, Different-sized Patches; Scrolling in Displacement "
            "Map Generation (snapping)",
        .params =
            {{"tri_size", LB_SPHERE_RINGS_TRI_SIZE, 3, 0.5, 64, false,
              "target triangle width in pixels (g_tessellatedTriSize)"},
             {"rings", LB_SPHERE_RINGS_RINGS, 0, 0, 8, true,
              "tile rings (8x8 tiles of 8x8 patches, inner 4x4 hole after the first; innermost patch = extent / grid); "
              "0 = the fewest covering the terrain from any camera, 1 + ceil(log2(grid / 32))"},
             {"pow2", LB_SPHERE_RINGS_POW2, 1, 0, 1, true,
              "1: power-of-2 levels at ring boundaries; 0: integer+even only (cracks)"}},
        .mainParam = "tri_size",
        .mainParamRole = MainParamRole::TriangleWidthPx,
        .front = {2, 4, 8},
        .topology = Topology::Quad4,
        .partitioning = Partitioning::FractionalEven,
        .tesc = "sphere_rings",
        .tese = "terrain_quad",
        .culls = true,
    };
    return kInfo;
  }

  PatchGeometry patchGeometry(const Heightfield& hf, const ParamValues& v, int grid) const override {
    return buildRings(hf, v, grid, true);
  }

  // Per frame: the ring centre, from the LOD eye (frame.lodEye) and terrain (frame.terrain).
  void update(FrameUniforms& frame, const ParamValues& values) const override {
    Scheme::update(frame, values);
    const int grid = int(frame.terrain.y);
    glm::ivec2 k(0);
    if (grid > 0 && frame.terrain.x > 0)
      k = ringCentre(glm::dvec2(double(frame.lodEye.x) - frame.origin.x, double(frame.lodEye.z) - frame.origin.y),
                     frame.terrain.x, grid, ringCount(values, grid));
    frame.params[LB_SPHERE_RINGS_CENTRE_X / 4][LB_SPHERE_RINGS_CENTRE_X % 4] = float(k.x);
    frame.params[LB_SPHERE_RINGS_CENTRE_Z / 4][LB_SPHERE_RINGS_CENTRE_Z % 4] = float(k.y);
  }

  // Ring boundaries are T-junctions, so cracks are counted on this mesh rather than the grid. The
  // layout is translation-invariant, so the local mesh has the topology of every frame's; patches
  // off the terrain that frame are culled (levels 0).
  PatchGeometry patchLayout(const Heightfield& hf, const ParamValues& v, int grid) const override {
    return buildRings(hf, v, grid, false);
  }
};

}  // namespace

int ringCount(const ParamValues& v, int grid) {
  int needed = 1;
  while ((kRingHalf << (needed - 1)) < grid) ++needed;
  const int rings = int(v.at("rings"));
  if (rings == 0) return needed;
  if (rings < needed)
    throw InputError("sphere-rings: rings = " + std::to_string(rings) +
                     " leaves part of the terrain uncovered at grid " + std::to_string(grid) +
                     " (needs >= " + std::to_string(needed) + ", or 0 for that)");
  return rings;
}

glm::ivec2 ringCentre(glm::dvec2 eyeXZ, double extent, int grid, int rings) {
  const long coarsest = 1L << (rings - 1), maxCentre = long(grid) / coarsest * coarsest;
  auto snap = [&](double world) {
    double cells = std::round(world / extent * grid / double(coarsest));
    return int(std::clamp(long(std::clamp(cells, -1e9, 1e9)) * coarsest, 0L, maxCentre));
  };
  return {snap(eyeXZ.x), snap(eyeXZ.y)};
}

long ringLatticeSize(int grid, int ring) {
  return (long(grid) + (1L << ring) - 1) >> ring;
}

const Scheme& sphereRingsScheme() {
  static const SphereRings scheme;
  return scheme;
}

}  // namespace lb
