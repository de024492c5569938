#version 450
#extension GL_GOOGLE_include_directive : require
// Accuracy baseline (docs/design.md, Schemes and What is measured): the densest crack-free tessellation, integer level
// min(64, maxTessellationGenerationLevel) on every edge and inside, no culling. Vulkan requires
// maxTessellationGenerationLevel >= 64, so the level is LB_MAX_FACTOR on every conformant device.
#include "common.glsl"
#include "tesc_common.glsl"

void main() {
  passThrough();
  if (gl_InvocationID == 0) writeLevels(vec4(LB_MAX_FACTOR), vec2(LB_MAX_FACTOR));
}
