#version 450
#extension GL_GOOGLE_include_directive : require
// Minimal loop: one uniform level on every edge and inside, no culling.
#include "probe.glsl"

layout(vertices = 4) out;
layout(location = 0) in vec2 inXZ[];
layout(location = 0) out vec2 outXZ[];

void main() {
  outXZ[gl_InvocationID] = inXZ[gl_InvocationID];
  if (gl_InvocationID == 0) {
    float l = probe.terrain.y;
    gl_TessLevelOuter[0] = gl_TessLevelOuter[1] = gl_TessLevelOuter[2] = gl_TessLevelOuter[3] = l;
    gl_TessLevelInner[0] = gl_TessLevelInner[1] = l;
  }
}
