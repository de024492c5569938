#version 450
#extension GL_GOOGLE_include_directive : require
// NVIDIA "DirectX 11 Terrain Tessellation" (Cantlay 2011), "Hull Shader: Tessellation LOD", the
// initial version the sample left commented out: project the displaced edge itself and divide its
// screen length by g_tessellatedTriSize. Figure 7: an edge almost parallel to the view vector has
// almost zero screen length, so a strongly displaced patch seen edge-on gets the minimum factor
// (severe aliasing). Kept as its own scheme so the failure shows next to `sphere`.
#include "common.glsl"
#include "sphere_edge_params.h"
#include "tesc_common.glsl"

// Screen length in pixels of the edge p0-p1 seen by the LOD camera; symmetric in p0 and p1, so
// both patches sharing the edge agree (crack-free like the sphere).
float edgeLevel(vec3 p0, vec3 p1) {
  vec4 c0 = frame.lodProj * (frame.lodView * vec4(p0, 1.0));
  vec4 c1 = frame.lodProj * (frame.lodView * vec4(p1, 1.0));
  // An end behind the near plane has no meaningful projection; such an edge is at the camera.
  if (c0.w <= 0.0 || c1.w <= 0.0) return LB_MAX_FACTOR;
  vec2 s0 = c0.xy / c0.w * 0.5 * frame.viewport.xy, s1 = c1.xy / c1.w * 0.5 * frame.viewport.xy;
  return clamp(distance(s0, s1) / schemeParam(LB_SPHERE_EDGE_TRI_SIZE), 1.0, LB_MAX_FACTOR);
}

void main() {
  passThrough();
  if (gl_InvocationID != 0) return;
  if (patchCulled()) {
    writeLevels(vec4(0.0), vec2(0.0));
    return;
  }
  vec4 outer = vec4(edgeLevel(inPos[0], inPos[3]), edgeLevel(inPos[0], inPos[1]),
                    edgeLevel(inPos[1], inPos[2]), edgeLevel(inPos[3], inPos[2]));
  vec2 inner = vec2(max(outer.y, outer.w), max(outer.x, outer.z));
  writeLevels(outer, inner);
}
