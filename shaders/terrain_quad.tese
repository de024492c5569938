#version 450
#extension GL_GOOGLE_include_directive : require
// Shared evaluation shader for quad patches: bilinear in the patch, height from the heightfield.
// Control points 0..3 are the corners (x,z), (x+1,z), (x+1,z+1), (x,z+1); 12-point patches add
// neighbour points after them, which evaluation ignores. SPACING is set per build variant.
#include "terrain_vertex.glsl"

layout(quads, SPACING, ccw) in;
layout(location = 0) in vec3 inPos[];

void main() {
  vec2 uv = gl_TessCoord.xy;
  vec3 a = mix(inPos[0], inPos[1], uv.x);
  vec3 b = mix(inPos[3], inPos[2], uv.x);
  vec2 xz = mix(a, b, uv.y).xz;
  vec3 world = vec3(xz.x, terrainHeight(xz), xz.y);
  // Heat map shows the edge level on patch borders and the inner level inside.
  float level = gl_TessLevelInner[0];
  if (uv.x == 0.0) level = gl_TessLevelOuter[0];
  else if (uv.y == 0.0) level = gl_TessLevelOuter[1];
  else if (uv.x == 1.0) level = gl_TessLevelOuter[2];
  else if (uv.y == 1.0) level = gl_TessLevelOuter[3];
  emitTerrainVertex(world, level);
}
