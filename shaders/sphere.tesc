#version 450
#extension GL_GOOGLE_include_directive : require
// NVIDIA "DirectX 11 Terrain Tessellation" (Cantlay 2011), "Hull Shader: Tessellation LOD" and
// "Crack-Free Tessellation": per edge, a sphere around the displaced edge is projected to the
// screen; factor = projected diameter / g_tessellatedTriSize. Edge factors depend only on the
// edge's two end points, so neighbours agree. Patches outside the frustum get factor 0 (culled).
#include "common.glsl"
#include "sphere_params.h"
#include "tesc_common.glsl"
#include "sphere_lod.glsl"

float edgeLevel(vec3 p0, vec3 p1) {
  // Behind the LOD camera the projection is meaningless; the patch is culled or partly visible.
  return sphereToScreenSpaceTessellation(p0, p1, distance(p0, p1), schemeParam(LB_SPHERE_TRI_SIZE));
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
  // Inner factors follow the edges parallel to each domain direction.
  vec2 inner = vec2(max(outer.y, outer.w), max(outer.x, outer.z));
  writeLevels(outer, inner);
}
