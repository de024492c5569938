// Shared GLSL: heightfield sampling (bit-for-bit the same as lb::Heightfield::sample), camera helpers.
#ifndef LB_COMMON_GLSL
#define LB_COMMON_GLSL
#include "shared.h"

layout(set = 0, binding = LB_BINDING_HEIGHT) uniform sampler2D heightMap;

float schemeParam(int i) { return frame.params[i / 4][i % 4]; }

float terrainExtent() { return frame.terrain.x; }

// Manual bilinear with texelFetch so CPU metrics can reproduce it exactly (at the origin; a far
// terrain origin rounds worldXZ first, which is the precision loss the far-origin scenario shows).
float terrainHeight(vec2 worldXZ) {
  ivec2 size = textureSize(heightMap, 0);
  vec2 t = clamp((worldXZ - frame.origin.xy) / frame.terrain.x, 0.0, 1.0) * vec2(size - 1);
  ivec2 i0 = min(ivec2(floor(t)), max(size - 2, ivec2(0)));
  vec2 f = t - vec2(i0);
  ivec2 i1 = min(i0 + 1, size - 1);
  float h00 = texelFetch(heightMap, i0, 0).r;
  float h10 = texelFetch(heightMap, ivec2(i1.x, i0.y), 0).r;
  float h01 = texelFetch(heightMap, ivec2(i0.x, i1.y), 0).r;
  float h11 = texelFetch(heightMap, i1, 0).r;
  return mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
}

// Normal from central differences of the heightfield, one texel apart.
vec3 terrainNormal(vec2 worldXZ) {
  ivec2 size = textureSize(heightMap, 0);
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
