#version 450
#extension GL_GOOGLE_include_directive : require
// practical-d3d11-ch9 9.1.2: the distance LOD of Listing 9.7 weighted by the coplanarity lookup
// that shaders/planefit.comp wrote (Listings 9.10-9.16). The book prints no hull shader for this
// step ("the exact weightings and biases can be easily tweaked"); here the distance term is
// multiplied by saturate(deviation / roughness), so a flat block gets min_lod even close by
// (Figure 9.23) and a block as rough as `roughness` gets the full distance LOD. fit = 1's deviation
// is in world units: compared with roughness x extent, so the weight is scale-free
// (schemes/planefit.cpp argues the extent).
// Crack-free: an edge's factor depends only on the edge (its midpoint, the blocks along it).
#include "common.glsl"
#include "planefit_params.h"
#include "tesc_common.glsl"
#include "distance_lod.glsl"

layout(set = 0, binding = LB_BINDING_SCHEME_TEX) uniform sampler2D planeFit;

int floorDiv(int a, int b) { return a / b; }  // a, b >= 0
int ceilDiv(int a, int b) { return (a + b - 1) / b; }

// Blocks along one axis for grid coordinates [g0, g1] (exact integers, no float rounding at block
// borders). A span (g0 < g1) takes the blocks its texel interval [t0, t1) overlaps; a line
// (g0 == g1) takes the blocks on both sides of it when it lies on a block border.
ivec2 blockSpan(int g0, int g1, int samples, int blocks) {
  int n = int(frame.terrain.y);
  int d = n * LB_PLANE_FIT_BLOCK;  // t / 16 = g * (samples - 1) / d
  int a0 = g0 * (samples - 1), a1 = g1 * (samples - 1);
  int lo = g0 == g1 ? ceilDiv(a0, d) - 1 : floorDiv(a0, d);
  int hi = g0 == g1 ? floorDiv(a1, d) : ceilDiv(a1, d) - 1;
  return clamp(ivec2(lo, hi), ivec2(0), ivec2(blocks - 1));
}

// Largest coplanarity deviation over the blocks that grid rectangle [g0, g1] covers.
float roughness(ivec2 g0, ivec2 g1) {
  ivec2 samples = terrainSamples(), blocks = textureSize(planeFit, 0);
  ivec2 bx = blockSpan(g0.x, g1.x, samples.x, blocks.x), bz = blockSpan(g0.y, g1.y, samples.y, blocks.y);
  float deviation = 0.0;
  for (int z = bz.x; z <= bz.y; ++z)
    for (int x = bx.x; x <= bx.y; ++x) deviation = max(deviation, texelFetch(planeFit, ivec2(x, z), 0).w);
  return deviation;
}

float weightedLod(vec3 p, ivec2 g0, ivec2 g1) {
  float unit = schemeParam(LB_PLANEFIT_FIT) > 0.5 ? terrainExtent() : 1.0;
  float weight = clamp(roughness(g0, g1) / (schemeParam(LB_PLANEFIT_ROUGHNESS) * unit), 0.0, 1.0);
  return mix(schemeParam(LB_PLANEFIT_MIN_LOD), schemeParam(LB_PLANEFIT_MAX_LOD), (1.0 - scaledDistance(p)) * weight);
}

void main() {
  passThrough();
  if (gl_InvocationID != 0) return;
  if (patchCulled()) {
    writeLevels(vec4(0.0), vec2(0.0));
    return;
  }
  int n = int(frame.terrain.y);
  ivec2 c = ivec2(int(patchIndex()) % n, int(patchIndex()) / n);  // grid corner c0
  vec3 mid = (inPos[0] + inPos[1] + inPos[2] + inPos[3]) * 0.25;
  vec4 outer = vec4(weightedLod(0.5 * (inPos[0] + inPos[3]), c, c + ivec2(0, 1)),
                    weightedLod(0.5 * (inPos[0] + inPos[1]), c, c + ivec2(1, 0)),
                    weightedLod(0.5 * (inPos[1] + inPos[2]), c + ivec2(1, 0), c + ivec2(1, 1)),
                    weightedLod(0.5 * (inPos[3] + inPos[2]), c + ivec2(0, 1), c + ivec2(1, 1)));
  writeLevels(outer, vec2(weightedLod(mid, c, c + ivec2(1, 1))));
}
