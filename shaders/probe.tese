#version 450
#extension GL_GOOGLE_include_directive : require
// Minimal loop: bilinear in the patch, height from the height map (as terrain_quad.tese).
#include "probe.glsl"

layout(quads, SPACING, ccw) in;
layout(location = 0) in vec2 inXZ[];

void main() {
  vec2 uv = gl_TessCoord.xy;
  vec2 xz = mix(mix(inXZ[0], inXZ[1], uv.x), mix(inXZ[3], inXZ[2], uv.x), uv.y);
  gl_Position = probe.viewProj * vec4(xz.x, probeHeight(xz), xz.y, 1.0);
}
