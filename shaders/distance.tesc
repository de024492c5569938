#version 450
#extension GL_GOOGLE_include_directive : require
// practical-d3d11-ch9, Listing 9.7 ComputePatchLOD from the patch midpoint (Listing 9.6); per-edge
// factors as in amd-detail-tessellation-11 "Distance-adaptive Tessellation" ("calculates the
// distance factor for each edge"). The book's 4-point version would give every edge of a patch its
// own midpoint LOD, which cracks between patches of different LOD; here each edge's factor is the
// same formula at the edge midpoint, a function of the two shared end points only, so both
// patches of an edge compute the same bits. Inner factors = the patch LOD (Listing 9.5).
#include "common.glsl"
#include "tesc_common.glsl"
#include "distance_lod.glsl"

float edgeLod(vec3 a, vec3 b) { return distanceLod(0.5 * (a + b)); }

void main() {
  passThrough();
  if (gl_InvocationID != 0) return;
  if (patchCulled()) {
    writeLevels(vec4(0.0), vec2(0.0));
    return;
  }
  vec3 mid = (inPos[0] + inPos[1] + inPos[2] + inPos[3]) * 0.25;  // ComputePatchMidPoint
  vec4 outer = vec4(edgeLod(inPos[0], inPos[3]), edgeLod(inPos[0], inPos[1]), edgeLod(inPos[1], inPos[2]),
                    edgeLod(inPos[3], inPos[2]));
  writeLevels(outer, vec2(distanceLod(mid)));
}
