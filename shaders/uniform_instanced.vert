#version 450
#extension GL_GOOGLE_include_directive : require
// `uniform`'s workload as instanced grids (harness/render/uniform_instanced.h): a tessellated
// patch's vertices, placed by instance: patch (i, j) of the base grid, `level` cells a side.
#define LB_INSTANCED_VERTEX
#include "terrain_vertex.glsl"
#include "uniform_params.h"

void main() {
  float level = schemeParam(LB_UNIFORM_LEVEL);
  vec2 patchIndex = instanceRecord().a.xy;
  // Integer lattice of level x grid cells a side; one expression for every vertex.
  vec2 lattice = patchIndex * level + inLattice;
  precise vec2 xz = frame.origin.xy + lattice * (frame.terrain.x / (frame.terrain.y * level));
  emitTerrainVertex(vec3(xz.x, terrainHeight(xz), xz.y), equivalentLevel(frame.terrain.x / (frame.terrain.y * level)));
}
