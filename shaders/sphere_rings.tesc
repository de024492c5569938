#version 450
#extension GL_GOOGLE_include_directive : require
// NVIDIA "DirectX 11 Terrain Tessellation" (Cantlay 2011), "Non-Uniform Patch Sizes" and
// "Implementation - Adjacency of Different-Sized Patches" (TerrainScreenspaceLODConstantsHS):
// sphere LOD per edge; on tile edges whose neighbour tile is half or twice our size, the two
// sides agree on integer, even (and by default power-of-2) levels with large = 2 x small.
#include "common.glsl"
#include "sphere_rings_params.h"
#include "tesc_common.glsl"
#include "sphere_lod.glsl"

const float kPatchesPerTile = 8.0;  // seed: 8x8 patches per tile

// Per patch, written by schemes/sphere_rings.cpp: the tile's neighbour sizes relative to ours on
// the sides -x, -z, +x, +z (outer-level order), then patch x, z within the tile, ring, patch size.
struct RingPatch {
  vec4 adjacency;
  vec4 tile;
};
layout(set = 0, binding = LB_BINDING_SCHEME_BUF, std430) readonly buffer Rings { RingPatch patches[]; } rings;

float triSize() { return schemeParam(LB_SPHERE_RINGS_TRI_SIZE); }
bool pow2Clamp() { return schemeParam(LB_SPHERE_RINGS_POW2) != 0.0; }

// Smallest power of two >= t, exact (frexp instead of log2, which may be off by an ulp).
float pow2Ceil(float t) {
  int e;
  float m = frexp(t, e);  // t = m * 2^e, m in [0.5, 1)
  return m == 0.5 ? t : ldexp(1.0, e);
}

// SmallerNeighbourAdjacencyClamp: we are the larger patch; the smaller side uses exactly half.
// Rounded up (no detail lost) to even, or to a power of 2; >= 4 because the smaller side's
// fractional_even minimum is 2.
float smallerNeighbourAdjacencyClamp(float t) {
  return max(pow2Clamp() ? pow2Ceil(t) : 2.0 * ceil(0.5 * t), 4.0);
}

// LargerNeighbourAdjacencyClamp: we are the smaller patch and halfT is half the larger neighbour's
// level; <= 32 because the larger side cannot exceed 64.
float largerNeighbourAdjacencyClamp(float halfT) {
  return clamp(pow2Clamp() ? pow2Ceil(halfT) : ceil(halfT), 2.0, 32.0);
}

void main() {
  passThrough();
  if (gl_InvocationID != 0) return;
  if (patchCulled()) {
    writeLevels(vec4(0.0), vec2(0.0));
    return;
  }
  RingPatch rp = rings.patches[patchIndex()];
  // Edge e in outer-level order: lower and upper corner along the edge, position along the edge
  // within the tile, and whether the edge lies on the tile's border on that side.
  const ivec2 kEnds[4] = ivec2[4](ivec2(0, 3), ivec2(0, 1), ivec2(1, 2), ivec2(3, 2));
  float along[4] = float[4](rp.tile.y, rp.tile.x, rp.tile.y, rp.tile.x);
  bool onBorder[4] = bool[4](rp.tile.x == 0.0, rp.tile.y == 0.0, rp.tile.x == kPatchesPerTile - 1.0,
                             rp.tile.y == kPatchesPerTile - 1.0);
  float outer[4];
  for (int e = 0; e < 4; ++e) {
    vec3 p0 = inPos[kEnds[e].x], p1 = inPos[kEnds[e].y];
    bool largerNeighbour = onBorder[e] && rp.adjacency[e] > 1.5;
    bool smallerNeighbour = onBorder[e] && rp.adjacency[e] < 0.75;
    // LargerNeighbourAdjacencyFix: two of our edges make one of the larger neighbour's; extend
    // ours to it, away from the other half (odd index: we are the upper half).
    if (largerNeighbour) {
      if (mod(along[e], 2.0) != 0.0) p0.xz += p0.xz - p1.xz;
      else p1.xz += p1.xz - p0.xz;
    }
    // MakeVertexHeightsAgree: every end point is re-sampled here with one code path, so both
    // sides of an edge see bit-identical heights (the vertex shader is a separate compilation).
    p0.y = terrainHeight(p0.xz);
    p1.y = terrainHeight(p1.xz);
    float t = sphereToScreenSpaceTessellation(p0, p1, distance(p0, p1), triSize());
    if (largerNeighbour) t = largerNeighbourAdjacencyClamp(0.5 * t);  // half: the edge is twice as long
    else if (smallerNeighbour) t = smallerNeighbourAdjacencyClamp(t);
    outer[e] = t;
  }
  // Seed: inner levels are the average of the two parallel edges ("visually looks OK").
  vec2 inner = vec2(0.5 * (outer[1] + outer[3]), 0.5 * (outer[0] + outer[2]));
  writeLevels(vec4(outer[0], outer[1], outer[2], outer[3]), inner);
}
