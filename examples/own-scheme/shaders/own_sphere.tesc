#version 450
#extension GL_GOOGLE_include_directive : require
// sphere's control shader (lodbench's shaders/sphere.tesc) under the plugin's name: per edge, the
// projected diameter of a sphere around the displaced edge / tri_size. common.glsl,
// tesc_common.glsl and sphere_lod.glsl are lodbench's shared includes.
#include "common.glsl"
#include "own_sphere_params.h"
#include "tesc_common.glsl"
#include "sphere_lod.glsl"

float edgeLevel(vec3 p0, vec3 p1) {
  return sphereToScreenSpaceTessellation(p0, p1, distance(p0, p1), schemeParam(LB_OWN_SPHERE_TRI_SIZE));
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
