#version 450
#extension GL_GOOGLE_include_directive : require
// cbt (schemes/cbt.cpp): one leaf of the tree, drawn as its triangle cut into 4^s micro-triangles.
// The footprint's (u, v), 0 <= u + v <= 2^s, walk from the right-angle corner b towards a and c;
// every step is a whole lattice unit, so corners and edges two leaves share are bit-identical.
#define LB_INSTANCED_VERTEX
#include "terrain_vertex.glsl"
#include "cbt_params.h"

void main() {
  InstanceRecord r = instanceRecord();
  vec2 a = r.a.xy, b = r.a.zw, c = r.b.xy;
  float n = exp2(schemeParam(LB_CBT_SUBD));
  precise vec2 lattice = b + inLattice.x * ((a - b) / n) + inLattice.y * ((c - b) / n);
  precise vec2 local = lattice * (frame.terrain.x / r.b.w);
  precise vec2 xz = frame.origin.xy + local;
  float cell = length(a - b) / n * (frame.terrain.x / r.b.w);
  emitTerrainVertex(vec3(xz.x, terrainHeight(xz), xz.y), equivalentLevel(cell));
}
