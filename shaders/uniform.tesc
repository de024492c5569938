#version 450
#extension GL_GOOGLE_include_directive : require
// Baseline: one fixed tessellation level on every edge and inside (integer partitioning).
#include "common.glsl"
#include "uniform_params.h"
#include "tesc_common.glsl"

void main() {
  passThrough();
  if (gl_InvocationID == 0) {
    float level = schemeParam(LB_UNIFORM_LEVEL);
    writeLevels(vec4(level), vec2(level));
  }
}
