// Shared GLSL: heightfield sampling (bit-for-bit the same as lb::Heightfield::sample), camera helpers.
#ifndef LB_COMMON_GLSL
#define LB_COMMON_GLSL
#include "shared.h"
#include "heights.glsl"

float schemeParam(int i) { return frame.params[i / 4][i % 4]; }

float terrainExtent() { return frame.terrain.x; }

// Manual bilinear with texelFetch so CPU metrics can reproduce it exactly (at the origin; a far
// terrain origin rounds worldXZ first, which is the precision loss the far-origin scenario shows).
// The corners come from the cell's page (heights.glsl); the arithmetic is the single image's.
float terrainHeight(vec2 worldXZ) {
  ivec2 size = terrainSamples();
  vec2 t = clamp((worldXZ - frame.origin.xy) / frame.terrain.x, 0.0, 1.0) * vec2(size - 1);
  ivec2 i0 = min(ivec2(floor(t)), max(size - 2, ivec2(0)));
  vec2 f = t - vec2(i0);
  vec4 h = cellCorners(i0);  // h00, h10, h01, h11
  return mix(mix(h.x, h.y, f.x), mix(h.z, h.w, f.x), f.y);
}

// Normal from central differences of the heightfield, one texel apart.
vec3 terrainNormal(vec2 worldXZ) {
  ivec2 size = terrainSamples();
  vec2 texel = frame.terrain.x / vec2(size - 1);
  float hl = terrainHeight(worldXZ - vec2(texel.x, 0));
  float hr = terrainHeight(worldXZ + vec2(texel.x, 0));
  float hd = terrainHeight(worldXZ - vec2(0, texel.y));
  float hu = terrainHeight(worldXZ + vec2(0, texel.y));
  return normalize(vec3((hl - hr) / (2.0 * texel.x), 1.0, (hd - hu) / (2.0 * texel.y)));
}

// True when the world-space box is entirely outside one culling frustum plane (the LOD camera's
// unless Renderer::setCullCamera says otherwise).
bool boxOutsideFrustum(vec3 lo, vec3 hi) {
  for (int i = 0; i < 6; ++i) {
    vec4 p = frame.frustum[i];
    vec3 v = vec3(p.x >= 0.0 ? hi.x : lo.x, p.y >= 0.0 ? hi.y : lo.y, p.z >= 0.0 ? hi.z : lo.z);
    if (dot(p.xyz, v) + p.w < 0.0) return true;
  }
  return false;
}

#endif
