#version 450
#extension GL_GOOGLE_include_directive : require
// Attribution variant of probe.tese: vec3 control points, as terrain_quad.tese reads them.
#include "probe.glsl"

layout(quads, SPACING, ccw) in;
layout(location = 0) in vec3 inPos[];

void main() {
  vec2 uv = gl_TessCoord.xy;
  vec2 xz = mix(mix(inPos[0], inPos[1], uv.x), mix(inPos[3], inPos[2], uv.x), uv.y).xz;
  gl_Position = probe.viewProj * vec4(xz.x, probeHeight(xz), xz.y, 1.0);
}
