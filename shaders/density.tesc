#version 450
#extension GL_GOOGLE_include_directive : require
// AMD "Detail Tessellation 11", Density-based Tessellation, and Rapp 2011, 5.2.3: each edge's
// screen-space factor (NVIDIA's projected edge sphere / tri_size, as in sphere.tesc) is multiplied
// by the maximum density along the edge, so flat ground gets few triangles and creases many. Both
// terms depend only on the edge, so neighbours agree. Patches outside the frustum get factor 0.
#include "common.glsl"
#include "density_params.h"
#include "tesc_common.glsl"
#include "sphere_lod.glsl"
#include "density.glsl"

float edgeLevel(vec3 p0, vec3 p1, ivec2 g0, ivec2 g1) {
  // Multiply before clamping, as the seed does (the tessellator clamps its product).
  float screen = sphereDiameterPixels(p0, p1, distance(p0, p1)) / schemeParam(LB_DENSITY_TRI_SIZE);
  float density = maxDensityAlongEdge(gridVertexTexel(g0), gridVertexTexel(g1));
  return clamp(screen * density, 1.0, LB_MAX_FACTOR);
}

void main() {
  passThrough();
  if (gl_InvocationID != 0) return;
  if (patchCulled()) {
    writeLevels(vec4(0.0), vec2(0.0));
    return;
  }
  // Grid vertices of the corners c0..c3: patch p = j * N + i.
  int n = int(frame.terrain.y);
  int p = int(patchIndex());
  ivec2 c0 = ivec2(p % n, p / n), c1 = c0 + ivec2(1, 0), c2 = c0 + ivec2(1, 1), c3 = c0 + ivec2(0, 1);
  vec4 outer = vec4(edgeLevel(inPos[0], inPos[3], c0, c3), edgeLevel(inPos[0], inPos[1], c0, c1),
                    edgeLevel(inPos[1], inPos[2], c1, c2), edgeLevel(inPos[3], inPos[2], c3, c2));
  // Inner factors follow the density-scaled edges parallel to each domain direction (as sphere.tesc).
  vec2 inner = vec2(max(outer.y, outer.w), max(outer.x, outer.z));
  writeLevels(outer, inner);
}
