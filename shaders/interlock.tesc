#version 450
#extension GL_GOOGLE_include_directive : require
// Practical Rendering & Computation with Direct3D 11, ch. 9.1.1 (Snook's interlocking tiles on the
// GPU), Listings 9.5-9.7: the 12-point patch holds this cell's corners plus two points of each
// neighbour cell; five midpoint LODs (own + 4 neighbours) from distance to the camera; inner = own
// LOD, each edge = min(own, neighbour) so the higher-detail side blends down to the lower one.
//
// Control points (render/patch_grid.cpp, Quad12): 0..3 corners (i,j) (i+1,j) (i+1,j+1) (i,j+1);
// 4,5 = (i-1,j) (i-1,j+1); 6,7 = (i,j-1) (i+1,j-1); 8,9 = (i+2,j) (i+2,j+1); 10,11 = (i,j+2)
// (i+1,j+2); clamped to the grid, so at the border a "neighbour" collapses onto the shared edge and
// its midpoint is the edge midpoint (Listing 9.2 and the text after Figure 9.5).
#include "common.glsl"
#include "interlock_params.h"
#include "tesc_common.glsl"

// Listing 9.6, with the corners always passed in the same grid order -- (a,b) (a+1,b) (a+1,b+1)
// (a,b+1) of the cell -- so both patches sharing an edge add the same floats in the same order.
// `precise` forbids fma contraction and reassociation, which could differ between call sites.
vec3 cellMidpoint(vec3 p00, vec3 p10, vec3 p11, vec3 p01) {
  precise vec3 sum = ((p00 + p10) + p11) + p01;
  precise vec3 mid = sum * 0.25;
  return mid;
}

// Listing 9.7 (ComputeScaledDistance + ComputePatchLOD), with the clamping the text describes.
// Distance written out (no dot/distance builtins) so every operation is covered by `precise`; in
// terrain extents, the unit of dmin and dmax (schemes/interlock.cpp).
float cellLod(vec3 midpoint) {
  float minDistance = schemeParam(LB_INTERLOCK_DMIN), maxDistance = schemeParam(LB_INTERLOCK_DMAX);
  float minLod = schemeParam(LB_INTERLOCK_MIN_LOD), maxLod = schemeParam(LB_INTERLOCK_MAX_LOD);
  precise vec3 d = midpoint - frame.lodEye.xyz;
  precise float dist = sqrt((d.x * d.x + d.y * d.y) + d.z * d.z) / terrainExtent();
  // dmin >= dmax degenerates to a step at dmin instead of dividing by 0.
  precise float scaled = clamp((dist - minDistance) / max(maxDistance - minDistance, 1e-6), 0.0, 1.0);
  precise float lod = minLod + (1.0 - scaled) * (maxLod - minLod);  // HLSL lerp(minLod, maxLod, 1 - d)
  return clamp(lod, 1.0, LB_MAX_FACTOR);
}

void main() {
  passThrough();
  if (gl_InvocationID != 0) return;
  // Not in Listing 9.5 (the book's D3D11 version draws every tile); the same per-patch frustum test
  // as the sphere scheme, switchable so cull=0 reproduces the book exactly.
  if (schemeParam(LB_INTERLOCK_CULL) != 0.0 && patchCulled()) {
    writeLevels(vec4(0.0), vec2(0.0));
    return;
  }
  float own = cellLod(cellMidpoint(inPos[0], inPos[1], inPos[2], inPos[3]));
  float lodU0 = cellLod(cellMidpoint(inPos[4], inPos[0], inPos[3], inPos[5]));    // cell (i-1,j)
  float lodV0 = cellLod(cellMidpoint(inPos[6], inPos[7], inPos[1], inPos[0]));    // cell (i,j-1)
  float lodU1 = cellLod(cellMidpoint(inPos[1], inPos[8], inPos[9], inPos[2]));    // cell (i+1,j)
  float lodV1 = cellLod(cellMidpoint(inPos[3], inPos[2], inPos[11], inPos[10]));  // cell (i,j+1)
  // The book's D3D order is U=0, V=0, U=1, V=1 with u along z; here u runs along x (c0 -> c1), so
  // Vulkan's outer[0] (u=0) faces (i-1,j), [1] (v=0) faces (i,j-1), [2] faces (i+1,j), [3] (i,j+1).
  // min() is exact and symmetric, so both sides of a shared edge get the same bits.
  vec4 outer = vec4(min(own, lodU0), min(own, lodV0), min(own, lodU1), min(own, lodV1));
  writeLevels(outer, vec2(own));
}
