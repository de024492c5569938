#version 450
#extension GL_GOOGLE_include_directive : require
// NVIDIA "DirectX 11 Terrain Tessellation" (Cantlay 2011), "Non-Uniform Patch Sizes" and
// "Implementation - Adjacency of Different-Sized Patches" (TerrainScreenspaceLODConstantsHS):
// sphere LOD per edge; on tile edges whose neighbour tile is half or twice our size, the two
// sides agree on integer, even (and by default power-of-2) levels with large = 2 x small.
// The rings follow the LOD camera: corners arrive in ring-local lattice units (one unit = extent /
// grid) and move by the per-frame centre update() writes (schemes/sphere_rings.cpp); the layout
// of the scheme buffer is schemes/sphere_rings_layout.h's.
#include "common.glsl"
#include "sphere_rings_params.h"
#include "tesc_common.glsl"
#include "sphere_lod.glsl"

const float kPatchesPerTile = 8.0;  // seed: 8x8 patches per tile

layout(set = 0, binding = LB_BINDING_SCHEME_BUF, std430) readonly buffer Rings { vec2 v[]; } rings;

float triSize() { return schemeParam(LB_SPHERE_RINGS_TRI_SIZE); }
bool pow2Clamp() { return schemeParam(LB_SPHERE_RINGS_POW2) != 0.0; }
vec2 ringCentre() { return vec2(schemeParam(LB_SPHERE_RINGS_CENTRE_X), schemeParam(LB_SPHERE_RINGS_CENTRE_Z)); }

// A lattice point (integer-valued floats: exact) on the terrain. Every corner, own or
// reconstructed, goes through this one function, so equal lattice points give equal bits.
vec3 worldPoint(vec2 lattice) {
  vec2 xz = (lattice + ringCentre()) * (frame.terrain.x / frame.terrain.y) + frame.origin.xy;
  return vec3(xz.x, terrainHeight(xz), xz.y);
}

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

// Off the terrain this frame, or outside the culling frustum: the box is the patch's world
// footprint and the exact height bounds of its cell on ring level `ring`'s world lattice.
bool ringPatchCulled(vec2 lo, int ring) {
  int n = int(frame.terrain.y);
  int cells = (n + (1 << ring) - 1) >> ring;
  ivec2 cell = ivec2(lo + ringCentre()) >> ring;  // exact: corners of ring r are multiples of 2^r
  if (any(lessThan(cell, ivec2(0))) || any(greaterThanEqual(cell, ivec2(cells)))) return true;
  vec2 hb = rings.v[int(rings.v[ring / 2][ring % 2]) + cell.y * cells + cell.x];
  vec3 a = worldPoint(lo), b = worldPoint(lo + vec2(1 << ring));
  return boxOutsideFrustum(vec3(a.x, hb.x, a.z), vec3(b.x, hb.y, b.z));
}

void main() {
  outPos[gl_InvocationID] = worldPoint(inPos[gl_InvocationID].xz);
  if (gl_InvocationID != 0) return;
  int base = int(rings.v[4].x) + 4 * int(patchIndex());
  vec4 adjacency = vec4(rings.v[base], rings.v[base + 1]);
  vec2 tile = rings.v[base + 2];
  int ring = int(rings.v[base + 3].x);
  if (ringPatchCulled(inPos[0].xz, ring)) {
    writeLevels(vec4(0.0), vec2(0.0));
    return;
  }
  // Edge e in outer-level order: lower and upper corner along the edge, position along the edge
  // within the tile, and whether the edge lies on the tile's border on that side.
  const ivec2 kEnds[4] = ivec2[4](ivec2(0, 3), ivec2(0, 1), ivec2(1, 2), ivec2(3, 2));
  float along[4] = float[4](tile.y, tile.x, tile.y, tile.x);
  bool onBorder[4] = bool[4](tile.x == 0.0, tile.y == 0.0, tile.x == kPatchesPerTile - 1.0, tile.y == kPatchesPerTile - 1.0);
  float outer[4];
  for (int e = 0; e < 4; ++e) {
    vec2 l0 = inPos[kEnds[e].x].xz, l1 = inPos[kEnds[e].y].xz;
    bool largerNeighbour = onBorder[e] && adjacency[e] > 1.5;
    bool smallerNeighbour = onBorder[e] && adjacency[e] < 0.75;
    // LargerNeighbourAdjacencyFix: two of our edges make one of the larger neighbour's; extend
    // ours to it, away from the other half (odd index: we are the upper half). In lattice units
    // the reconstruction is exact.
    if (largerNeighbour) {
      if (mod(along[e], 2.0) != 0.0) l0 += l0 - l1;
      else l1 += l1 - l0;
    }
    // MakeVertexHeightsAgree: every end point is sampled here with one code path, so both sides
    // of an edge see bit-identical positions and heights.
    vec3 p0 = worldPoint(l0), p1 = worldPoint(l1);
    float t = sphereToScreenSpaceTessellation(p0, p1, distance(p0, p1), triSize());
    if (largerNeighbour) t = largerNeighbourAdjacencyClamp(0.5 * t);  // half: the edge is twice as long
    else if (smallerNeighbour) t = smallerNeighbourAdjacencyClamp(t);
    outer[e] = t;
  }
  // Seed: inner levels are the average of the two parallel edges ("visually looks OK").
  vec2 inner = vec2(0.5 * (outer[1] + outer[3]), 0.5 * (outer[0] + outer[2]));
  writeLevels(vec4(outer[0], outer[1], outer[2], outer[3]), inner);
}
