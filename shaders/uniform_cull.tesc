#version 450
#extension GL_GOOGLE_include_directive : require
// uniform's one fixed level (integer partitioning), and factor 0 for a patch outside the frustum
// as sphere.tesc culls: schemes/uniform_cull.cpp says what the pair measures.
#include "common.glsl"
#include "uniform_params.h"
#include "tesc_common.glsl"

void main() {
  passThrough();
  if (gl_InvocationID != 0) return;
  if (patchCulled()) {
    writeLevels(vec4(0.0), vec2(0.0));
    return;
  }
  float level = schemeParam(LB_UNIFORM_LEVEL);
  writeLevels(vec4(level), vec2(level));
}
