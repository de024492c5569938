#version 450
#extension GL_GOOGLE_include_directive : require
// Rapp 2011, 5.2.4 (Figure 5-11 and the text after it): triangle patches; a triangle is dropped when
// all corners lie beyond one side (or the near) plane by more than a tolerance, or when all three
// edge normals face away from the eye by more than a tolerance; otherwise edge factor = edge length
// on screen / desired triangle size, inner = mean of the edges, then each is multiplied by the
// density (per edge the maximum along the edge, inside the largest of the three). fractional_odd.
// The control points carry unit vertex normals and the shape factor for terrain_tri.tese.
#include "common.glsl"
#include "phong_params.h"
#include "tesc_tri_common.glsl"
#include "density.glsl"

layout(location = 1) out vec3 outNormal[];
layout(location = 2) patch out float outShape;

// Pixel position of a world point seen by the LOD camera (GetScreenSpacePosition of the AMD samples
// the thesis builds on); false when the point is not in front of the camera.
bool lodPixelPosition(vec3 p, out vec2 px) {
  vec4 clip = frame.lodProj * (frame.lodView * vec4(p, 1.0));
  px = clip.xy / clip.w * 0.5 * frame.viewport.xy;
  return clip.w > 0.0;
}

// Vertex normal of the base grid: central differences one grid cell apart (5.2.2 averages the
// adjacent faces; its grid matches the heightmap, where this equals terrainNormal()).
vec3 gridNormal(vec2 xz) {
  float d = frame.terrain.x / frame.terrain.y;
  float hl = terrainHeight(xz - vec2(d, 0)), hr = terrainHeight(xz + vec2(d, 0));
  float hd = terrainHeight(xz - vec2(0, d)), hu = terrainHeight(xz + vec2(0, d));
  return normalize(vec3((hl - hr) / (2.0 * d), 1.0, (hd - hu) / (2.0 * d)));
}

// Outside when all three corners are more than `margin` beyond one of the left, right, bottom and
// top planes (the thesis tests those four) or the near plane (without it the margin would keep
// triangles just behind the eye). Phong moves a point by at most alpha * longest edge, so a margin
// of at least that never drops a visible triangle.
bool outsideFrustum(float margin) {
  for (int i = 0; i < 5; ++i) {
    vec4 plane = frame.frustum[i];
    bool allOut = true;
    for (int k = 0; k < 3; ++k) allOut = allOut && dot(plane.xyz, inPos[k]) + plane.w <= -margin;
    if (allOut) return true;
  }
  return false;
}

// Back facing when, for every edge, the mean of its end normals points away from the eye (seen from
// the edge midpoint) with a dot product <= -tolerance; the tolerance keeps silhouette triangles.
bool backFacing(float tolerance) {
  for (int k = 0; k < 3; ++k) {
    int a = (k + 1) % 3, b = (k + 2) % 3;
    vec3 edgeNormal = normalize(outNormal[a] + outNormal[b]);
    vec3 toEye = normalize(frame.lodEye.xyz - 0.5 * (inPos[a] + inPos[b]));
    if (dot(edgeNormal, toEye) > -tolerance) return false;
  }
  return true;
}

void main() {
  passThrough();
  outNormal[gl_InvocationID] = gridNormal(inPos[gl_InvocationID].xz);
  barrier();  // invocation 0 reads every corner's normal below
  if (gl_InvocationID != 0) return;
  outShape = schemeParam(LB_PHONG_ALPHA);
  float longest = max(max(distance(inPos[0], inPos[1]), distance(inPos[1], inPos[2])), distance(inPos[2], inPos[0]));
  if (outsideFrustum(schemeParam(LB_PHONG_FRUSTUM_TOLERANCE) * longest) || backFacing(schemeParam(LB_PHONG_BACKFACE_TOLERANCE))) {
    writeTriLevels(vec3(0.0), 0.0);
    return;
  }
  vec2 px[3];
  bool front[3];
  ivec2 texel[3];
  for (int k = 0; k < 3; ++k) {
    front[k] = lodPixelPosition(inPos[k], px[k]);
    texel[k] = gridVertexTexel(triGridVertex(k));
  }
  // Edge k is opposite corner k. An edge reaching behind the eye passes next to it: finest level.
  vec3 screen, density;
  for (int k = 0; k < 3; ++k) {
    int a = (k + 1) % 3, b = (k + 2) % 3;
    screen[k] = front[a] && front[b] ? distance(px[a], px[b]) / schemeParam(LB_PHONG_TRI_SIZE) : LB_MAX_FACTOR;
    density[k] = maxDensityAlongEdge(texel[a], texel[b]);
  }
  float inner = (screen.x + screen.y + screen.z) / 3.0 * max(max(density.x, density.y), density.z);
  writeTriLevels(clamp(screen * density, 1.0, LB_MAX_FACTOR), clamp(inner, 1.0, LB_MAX_FACTOR));
}
