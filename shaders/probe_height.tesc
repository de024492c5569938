#version 450
#extension GL_GOOGLE_include_directive : require
// Attribution variant of probe.tesc: passes the displaced control point (vec3) as lodbench does.
#include "probe.glsl"

layout(vertices = 4) out;
layout(location = 0) in vec3 inPos[];
layout(location = 0) out vec3 outPos[];

void main() {
  outPos[gl_InvocationID] = inPos[gl_InvocationID];
  if (gl_InvocationID == 0) {
    float l = probe.terrain.y;
    gl_TessLevelOuter[0] = gl_TessLevelOuter[1] = gl_TessLevelOuter[2] = gl_TessLevelOuter[3] = l;
    gl_TessLevelInner[0] = gl_TessLevelInner[1] = l;
  }
}
