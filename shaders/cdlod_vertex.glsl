// cdlod and cdlod-sse (schemes/cdlod.cpp): vertex g of a quadrant's footprint, g = (x, z) with x, z in
// 0..side, placed and morphed by the quadrant's instance record (shaders/cdlod_params.h). One
// function for the instanced grid (shaders/cdlod.vert) and the mesh path (shaders/cdlod_ms.mesh), so
// both draw a node's vertices from the same arithmetic.
//
// The footprint of side x side cells is scaled by 2^level and morphed towards the next coarser grid.
// Odd vertices (at the node's scale) slide to their lower even neighbour by k cells; at k = 1 every
// 2 x 2 block is the coarse cell (plus zero-area triangles), so a fully morphed edge lies on its
// coarser neighbour's vertices. Morph factor: by the vertex's distance to the LOD eye (cdlod,
// Strugar's vertex shader), or given per node and per edge by the CPU (cdlod-sse, or cdlod with
// morph_on = 0: all zero).
#include "cdlod_params.h"

// The world point; `level` gets the heat map's equivalent level.
vec3 cdlodVertex(InstanceRecord r, vec2 g, out float level) {
  float q = schemeParam(LB_CDLOD_CELLS_PER_TEXEL);
  float side = floor(r.a.z / LB_CDLOD_SIDE_SHIFT);
  float nodeLevel = r.a.z - LB_CDLOD_SIDE_SHIFT * side;
  float scale = exp2(nodeLevel);
  // Terrain-local lattice, clamped to the last sample: vertices past the border collapse onto it.
  vec2 last = (frame.terrain.zw - 1.0) * q;
  vec2 odd = g - 2.0 * floor(g * 0.5);
  precise vec2 lattice = r.a.xy + g * scale;
  vec2 kAxes;
  float kLevel;
  if (r.a.w < 0.0) {
    vec2 xz = latticeToWorld(min(lattice, last), q);
    float d = distance(frame.lodEye.xyz, vec3(xz.x, terrainHeight(xz), xz.y));
    float k = r.b.y > r.b.x ? clamp((d - r.b.x) / (r.b.y - r.b.x), 0.0, 1.0) : (d >= r.b.x ? 1.0 : 0.0);
    kAxes = vec2(k);
    kLevel = k;
  } else {
    // x moves on a horizontal edge with that edge's factor, z on a vertical one: the two quadrants
    // sharing the edge hold the same factor for it, so its vertices agree bit for bit.
    bool west = g.x == 0.0, east = g.x == side, south = g.y == 0.0, north = g.y == side;
    kAxes.x = south ? r.b.y : (north ? r.b.w : r.a.w);
    kAxes.y = west ? r.b.x : (east ? r.b.z : r.a.w);
    kLevel = west || east ? kAxes.y : (south || north ? kAxes.x : r.a.w);
  }
  precise vec2 morphed = lattice - odd * kAxes * scale;
  vec2 xz = latticeToWorld(min(morphed, last), q);
  float cell = max(latticeCell(q).x, latticeCell(q).y) * scale * (1.0 + kLevel);
  level = equivalentLevel(cell);
  return vec3(xz.x, terrainHeight(xz), xz.y);
}
