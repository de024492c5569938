#version 450
#extension GL_GOOGLE_include_directive : require
// errbound (not from the seeds; schemes/errbound.cpp documents the bound): per patch the smallest
// power-of-two level whose precomputed deviation, projected at the patch's nearest visible view
// depth, stays under max_error_px; edges take the max of both patches' levels (the neighbour's
// level is computed here by the same function from the same inputs, so both sides agree).
#include "common.glsl"
#include "errbound_params.h"
#include "tesc_common.glsl"

// Per patch (i, j): texels (2i, j) and (2i+1, j) hold the deviation of levels 1, 2, 4, ..., 64.
layout(set = 0, binding = LB_BINDING_SCHEME_TEX) uniform sampler2D deviationTable;

float deviation(ivec2 g, int k) { return texelFetch(deviationTable, ivec2(2 * g.x + k / 4, g.y), 0)[k % 4]; }

float viewDepth(vec3 p) { return -(frame.lodView * vec4(p, 1.0)).z; }

// Smallest view depth over the part of the box (corners c, depths d) inside one frustum plane:
// box corners inside and box edges crossing the plane (depth is linear, so exact). 1e30 if none.
float minDepthInside(vec3 c[8], float d[8], vec4 plane) {
  float s[8];
  for (int k = 0; k < 8; ++k) s[k] = dot(plane.xyz, c[k]) + plane.w;
  float m = 1e30;
  for (int k = 0; k < 8; ++k) {
    if (s[k] >= 0.0) m = min(m, d[k]);
    for (int b = 1; b < 8; b <<= 1) {
      int j = k | b;
      if ((k & b) == 0 && (s[k] >= 0.0) != (s[j] >= 0.0)) m = min(m, mix(d[k], d[j], s[k] / (s[k] - s[j])));
    }
  }
  return m;
}

// Largest |d(screen point)/d(height)| * depth / K over the screen: a vertical step of length h at
// view depth w moves the projection by h * K / w * |(u.x, u.y) - q * u.w| (u = world up in view
// space, q = screen point over K); convex in q, so its maximum over the screen is at a corner.
float offAxisFactor() {
  vec3 u = (frame.lodView * vec4(0.0, 1.0, 0.0, 0.0)).xyz;
  vec2 halfScreen = vec2(1.0 / frame.lodProj[0][0], 1.0 / abs(frame.lodProj[1][1]));
  float s = 0.0;
  for (int i = 0; i < 4; ++i) {
    vec2 q = halfScreen * vec2((i & 1) != 0 ? 1.0 : -1.0, (i & 2) != 0 ? 1.0 : -1.0);
    s = max(s, length(u.xy + q * u.z));  // u.w = -u.z
  }
  return s;
}

// Level index k (level 2^k) of patch g; unmet when even level 64 exceeds the bound (then k = 6);
// px = the bound in pixels that level gives.
int levelIndex(ivec2 g, out bool unmet, out float px) {
  int n = int(frame.terrain.y);
  float extent = terrainExtent();
  vec2 hb = patchBounds.bounds[g.y * n + g.x];
  vec3 c[8];
  float d[8];
  for (int k = 0; k < 8; ++k) {
    // World position: the terrain's corner sits at frame.origin (far-origin scenario).
    c[k] = vec3(frame.origin.x + extent * float(g.x + (k & 1)) / float(n), (k & 2) != 0 ? hb.y : hb.x,
                frame.origin.y + extent * float(g.y + ((k >> 2) & 1)) / float(n));
    d[k] = viewDepth(c[k]);
  }
  mat4 vp = frame.lodProj * frame.lodView;
  vec4 r0 = vec4(vp[0][0], vp[1][0], vp[2][0], vp[3][0]), r1 = vec4(vp[0][1], vp[1][1], vp[2][1], vp[3][1]);
  vec4 r3 = vec4(vp[0][3], vp[1][3], vp[2][3], vp[3][3]);
  // Nearest depth of what can be on screen: the near plane (cameraMatrices: extent * 1e-4) and
  // each side plane of the LOD frustum separately (each gives a lower bound of the joint minimum).
  float w = extent * 1e-4;
  w = max(w, minDepthInside(c, d, r3 + r0));
  w = max(w, minDepthInside(c, d, r3 - r0));
  w = max(w, minDepthInside(c, d, r3 + r1));
  w = max(w, minDepthInside(c, d, r3 - r1));
  float pxPerUnit = frame.viewport.y * 0.5 * abs(frame.lodProj[1][1]) * offAxisFactor() / w;
  float bound = schemeParam(LB_ERRBOUND_MAX_ERROR_PX);
  for (int k = 0; k < 7; ++k) {
    px = deviation(g, k) * pxPerUnit;
    if (px <= bound) {
      unmet = false;
      return k;
    }
  }
  unmet = true;
  return 6;
}

void main() {
  passThrough();
  if (gl_InvocationID != 0) return;
  uint base = patchIndex() * LB_CAPTURE_STRIDE;
  if (patchCulled()) {
    writeLevels(vec4(0.0), vec2(0.0));
    if (kCapture) capture.levels[base + LB_ERRBOUND_CAPTURE_UNMET] = 0.0;
    return;
  }
  int n = int(frame.terrain.y);
  ivec2 g = ivec2(int(patchIndex()) % n, int(patchIndex()) / n);
  bool unmet, unused;
  float px, unusedPx;
  float own = float(1 << levelIndex(g, unmet, px));
  vec4 outer = vec4(own);
  const ivec2 across[4] = ivec2[](ivec2(-1, 0), ivec2(0, -1), ivec2(1, 0), ivec2(0, 1));  // u=0, v=0, u=1, v=1
  for (int e = 0; e < 4; ++e) {
    ivec2 q = g + across[e];
    if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(n))))
      outer[e] = max(own, float(1 << levelIndex(q, unused, unusedPx)));
  }
  writeLevels(outer, vec2(own));
  if (kCapture) capture.levels[base + LB_ERRBOUND_CAPTURE_UNMET] = unmet ? 1.0 : 0.0;
}
