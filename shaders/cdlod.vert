#version 450
#extension GL_GOOGLE_include_directive : require
// cdlod and cdlod-sse (schemes/cdlod.cpp): one quadrant of a quadtree node, its footprint vertex
// placed and morphed as shaders/cdlod_vertex.glsl says.
#define LB_INSTANCED_VERTEX
#include "terrain_vertex.glsl"
#include "cdlod_vertex.glsl"

void main() {
  float level;
  vec3 world = cdlodVertex(instanceRecord(), inLattice, level);
  emitTerrainVertex(world, level);
}
