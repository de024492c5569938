#version 450
#extension GL_GOOGLE_include_directive : require
// chunked (schemes/chunked.cpp): a vertex of a chunk's precomputed mesh, at its heightfield sample,
// or a skirt's bottom vertex, the skirt depth below its sample (schemes/preprocess/chunk_tree.h).
#define LB_INSTANCED_VERTEX
#include "terrain_vertex.glsl"
#include "chunked_params.h"

void main() {
  InstanceRecord r = instanceRecord();
  vec2 g = inLattice;
  bool bottom = g.x < 0.0;
  if (bottom) g.x = -g.x - 1.0;
  vec2 xz = latticeToWorld(g, 1.0);
  // Both chunks beside a side compute a bottom vertex from the same integers and the same depth,
  // so their walls meet bit for bit.
  precise float h = terrainHeight(xz) - (bottom ? r.a.x : 0.0);
  vec2 cell = latticeCell(1.0);
  emitTerrainVertex(vec3(xz.x, h, xz.y), equivalentLevel(max(cell.x, cell.y) * exp2(r.a.y)));
}
