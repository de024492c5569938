#version 450
#extension GL_GOOGLE_include_directive : require
// cbt-ts: a micro-vertex of the leaf. At integer spacing and level n = 2^subd the domain
// coordinates are multiples of 1/n, so rounding them gives whole lattice steps and the vertex is
// the one cbt.vert computes for the same (u, v), bit for bit.
#include "terrain_vertex.glsl"
#include "cbt_params.h"

layout(triangles, SPACING, ccw) in;
layout(location = 0) in vec2 inCorner[];
layout(location = 1) in float inSquare[];

void main() {
  vec2 a = inCorner[0], b = inCorner[1], c = inCorner[2];
  float n = exp2(schemeParam(LB_CBT_SUBD));
  vec3 k = round(gl_TessCoord * n);
  precise vec2 lattice = b + k.x * ((a - b) / n) + k.z * ((c - b) / n);
  precise vec2 local = lattice * (frame.terrain.x / inSquare[0]);
  precise vec2 xz = frame.origin.xy + local;
  float cell = length(a - b) / n * (frame.terrain.x / inSquare[0]);
  emitTerrainVertex(vec3(xz.x, terrainHeight(xz), xz.y), equivalentLevel(cell));
}
