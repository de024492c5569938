#version 450
#extension GL_GOOGLE_include_directive : require
// TEST ONLY (tests/crack_scheme.cpp, not in the registry): sphere LOD (as shaders/sphere.tesc) with
// a deliberate crack: on every patch (i, j) with i + j even, the u=1 edge (x = i+1, shared with
// patch (i+1, j)) gets twice the sphere level (or half of it above 32), which always differs from
// the level the neighbour computes for the same edge. The crack detectors must find these edges.
#include "common.glsl"
#include "sphere_params.h"
#include "tesc_common.glsl"
#include "sphere_lod.glsl"

float edgeLevel(vec3 p0, vec3 p1) {
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
  int n = int(frame.terrain.y), p = int(patchIndex());
  if (((p % n) + (p / n)) % 2 == 0) outer.z = outer.z <= 32.0 ? 2.0 * outer.z : 0.5 * outer.z;
  vec2 inner = vec2(max(outer.y, outer.w), max(outer.x, outer.z));
  writeLevels(outer, inner);
}
