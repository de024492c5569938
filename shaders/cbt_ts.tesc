#version 450
#extension GL_GOOGLE_include_directive : require
// cbt-ts: every leaf tessellated at level 2^subd on all edges (integer spacing), which yields
// exactly cbt's 4^subd micro-triangles and micro-vertices.
#include "common.glsl"
#include "cbt_params.h"

layout(vertices = 3) out;
layout(location = 0) in vec2 inCorner[];
layout(location = 1) in float inSquare[];
layout(location = 0) out vec2 outCorner[];
layout(location = 1) out float outSquare[];

void main() {
  outCorner[gl_InvocationID] = inCorner[gl_InvocationID];
  outSquare[gl_InvocationID] = inSquare[gl_InvocationID];
  if (gl_InvocationID == 0) {
    float n = exp2(schemeParam(LB_CBT_SUBD));
    gl_TessLevelOuter[0] = n;
    gl_TessLevelOuter[1] = n;
    gl_TessLevelOuter[2] = n;
    gl_TessLevelInner[0] = n;
  }
}
