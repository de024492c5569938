#version 450
#extension GL_GOOGLE_include_directive : require
// cbt-ts: a vertex of the tessellated leaf (integer spacing, level n = 2^subd on every edge, as
// LEB2D's TS pipeline). The triangle domain is cut in concentric rings, so only the edges' vertices
// fall on cbt's micro-lattice: on an edge (one domain coordinate 0) the others are multiples of
// 1/n, rounded to whole lattice steps, so a vertex two leaves share is bit-identical in both; inside,
// the point is interpolated.
#include "terrain_vertex.glsl"
#include "cbt_params.h"

layout(triangles, SPACING, ccw) in;
layout(location = 0) in vec2 inCorner[];
layout(location = 1) in float inSquare[];

void main() {
  vec2 a = inCorner[0], b = inCorner[1], c = inCorner[2];
  float n = exp2(schemeParam(LB_CBT_SUBD));
  vec3 t = gl_TessCoord;
  precise vec2 lattice;
  if (min(t.x, min(t.y, t.z)) < 1e-6) {
    vec3 k = round(t * n);
    lattice = b + k.x * ((a - b) / n) + k.z * ((c - b) / n);
  } else {
    lattice = t.x * a + t.y * b + t.z * c;
  }
  precise vec2 local = lattice * (frame.terrain.x / inSquare[0]);
  precise vec2 xz = frame.origin.xy + local;
  float cell = length(a - b) / n * (frame.terrain.x / inSquare[0]);
  emitTerrainVertex(vec3(xz.x, terrainHeight(xz), xz.y), equivalentLevel(cell));
}
