#version 450
#extension GL_GOOGLE_include_directive : require
// Geometry clipmaps (schemes/clipmap.cpp): places a footprint vertex of one level and blends its
// height towards the next coarser level's surface near the level's border (paper 2.3.5). xz never
// moves: a vertex stays on its lattice point, only its height changes.
//
// Record: a = (origin x, z in finest lattice units, spacing g = 2^l, l); b = (eye x, z in level
// units, transition width w (0: no blend, the coarsest level), (n - 1) / 2 - w - 1).
#define LB_INSTANCED_VERTEX
#include "terrain_vertex.glsl"
#include "clipmap_params.h"

float cellsPerTexel() { return schemeParam(LB_CLIPMAP_CELLS_PER_TEXEL); }

// The terrain's height at a lattice point, clamped to the border in lattice units.
float latticeHeight(vec2 lattice) {
  vec2 last = (frame.terrain.zw - 1.0) * cellsPerTexel();
  return terrainHeight(latticeToWorld(clamp(lattice, vec2(0.0), last), cellsPerTexel()));
}

void main() {
  InstanceRecord r = instanceRecord();
  float g = r.a.z;
  int level = int(r.a.w);
  // Integers below 2^24: exact, so instances sharing a vertex compute the same lattice point.
  precise vec2 lattice = r.a.xy + inLattice * g;
  ivec2 cell = ivec2(lattice) >> level;  // the vertex in its level's units (arithmetic shift: floor)
  ivec2 odd = cell & 1;

  // The coarser level's surface through the vertex: itself on its even points, else the mean of the
  // ends of the coarse edge it halves (the cell diagonal (0,0)-(1,1) when both coordinates are odd).
  float h = latticeHeight(lattice);
  float hc = h;
  if (odd.x + odd.y > 0) {
    vec2 step = vec2(odd) * g;
    hc = 0.5 * (latticeHeight(lattice - step) + latticeHeight(lattice + step));
  }

  // alpha = 1 exactly where the argument reaches w: the comparison, not the division (2.5 ulp on a
  // GPU), decides it, and every operation before it is an exact or correctly rounded add.
  float w = r.b.z;
  float alpha = 0.0;
  if (w > 0.0) {
    precise vec2 t = abs(vec2(cell) - r.b.xy) - r.b.w;
    float tm = max(t.x, t.y);
    alpha = tm >= w ? 1.0 : clamp(tm / w, 0.0, 1.0);
  }
  // Exact at both ends: alpha = 0 gives h, alpha = 1 gives hc, whichever way the compiler fuses it.
  precise float height = (1.0 - alpha) * h + alpha * hc;

  vec2 last = (frame.terrain.zw - 1.0) * cellsPerTexel();
  vec2 xz = latticeToWorld(clamp(lattice, vec2(0.0), last), cellsPerTexel());
  vec2 c = latticeCell(cellsPerTexel());
  emitTerrainVertex(vec3(xz.x, height, xz.y), equivalentLevel(g * max(c.x, c.y)));
}
