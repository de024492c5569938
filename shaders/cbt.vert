#version 450
#extension GL_GOOGLE_include_directive : require
// cbt (schemes/cbt.cpp): one leaf of the tree, drawn as its triangle cut into 4^s micro-triangles
// (shaders/cbt_leaf.glsl): the footprint's vertex (u, v).
#define LB_INSTANCED_VERTEX
#include "terrain_vertex.glsl"
#include "cbt_leaf.glsl"

void main() {
  float level;
  vec3 world = cbtLeafPoint(instanceRecord(), inLattice, level);
  emitTerrainVertex(world, level);
}
