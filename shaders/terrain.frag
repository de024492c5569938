#version 450
#extension GL_GOOGLE_include_directive : require
// Identical shading for every scheme: per-pixel normals from the terrain's normal map (filtered at
// the level of the pixel's footprint, footprint.h), one directional light. A map that fits one image
// is read by the sampler's trilinear filter; one past it from its pages (normals.glsl) where a
// pixel is finer than its coarse levels, which are one image too.
#include "common.glsl"
#include "footprint.h"
#include "normals.glsl"

layout(constant_id = 0) const int kMode = LB_MODE_SHADED;
// Testing only (RenderSettings::testHeightNormals): the pre-issue-13 normal, rebuilt per pixel from
// four bilinear height lookups, so tests can compare images and counters with it.
layout(constant_id = 1) const bool kHeightNormals = false;
// Testing only (RenderSettings::testMipZeroShading): every pixel shaded from level 0.
layout(constant_id = 2) const bool kMipZero = false;
// The map is in pages (render/normal_pages.h): past one image, or pages asked for in a test.
layout(constant_id = 3) const bool kNormalPaged = false;
layout(set = 0, binding = LB_BINDING_NORMAL) uniform sampler2D normalMap;
layout(location = 0) in vec3 inWorld;
layout(location = 1) in float inLevel;
layout(location = 0) out vec4 outColor;

vec3 heat(float level) {
  // log2 scale: 1 -> blue, 8 -> green, 64 -> red
  float t = clamp(log2(max(level, 1.0)) / 6.0, 0.0, 1.0);
  return clamp(vec3(1.5 - abs(4.0 * t - 3.0), 1.5 - abs(4.0 * t - 2.0), 1.5 - abs(4.0 * t - 1.0)), 0.0, 1.0);
}

// Texel coordinate t as terrainHeight() computes it (texel i's centre at i), so level 0's filtered
// gradient is the one terrainNormal() computes; the level is the footprint's of this point as the
// ray-cast truth computes it for its hit (shadingLevel); lb::sampleNormalMap is the CPU twin.
vec3 mapNormal(vec3 world) {
  vec2 size = frame.terrain.zw;
  vec2 t = clamp((world.xz - frame.origin.xy) / frame.terrain.x, 0.0, 1.0) * (size - 1.0);
  float level = kMipZero ? 0.0 : shadingLevel(world, frame.shading.xyz, frame.shading.w, frame.terrain.x, int(size.x), int(size.y));
  if (kNormalPaged) {
    // Levels from normalCoarseFrom() on are also one image, read as an unpaged map is (its level 0
    // is that level; the same texel coordinates and fraction): only finer pixels take the pages.
    const float coarse = float(normalCoarseFrom());
    if (level < coarse) return nsMapNormal(t, level, normalLevels());
    level -= coarse;
  }
  vec2 g = textureLod(normalMap, (t + 0.5) / size, level).rg;
  return normalize(vec3(g.x, 1.0, g.y));
}

// The screen-space error of a drawn pixel: the on-screen length of the vertical segment from the
// drawn point to the true surface point at the same x, z. A true point at or behind the near plane
// (steep relief beside a low camera that looks down) has no projection, and one just in front of it
// projects arbitrarily far, so the segment is cut where it crosses the near plane (clip z = 0 with
// GLM's zero-to-one depth) and the length is capped at the viewport's diagonal: every pixel's error
// is finite, continuous in the geometry, at most the diagonal, and scale-free (the near plane scales
// with the terrain). docs/results-format.md states the same rule.
vec2 toPixels(vec4 c) {
  return c.xy / c.w * 0.5 * frame.viewport.xy;
}

float screenError(vec3 drawn, vec3 truth) {
  vec4 a = frame.viewProj * vec4(drawn, 1.0), b = frame.viewProj * vec4(truth, 1.0);
  float az = max(a.z, 0.0);  // a rasterised point is in front of the near plane up to rounding
  if (b.z < 0.0) b = mix(a, b, az / (az - b.z));
  // A point on the near plane keeps w = near > 0; the cap bounds what its projection yields.
  float diagonal = length(frame.viewport.xy);
  float len = distance(toPixels(a), toPixels(b));
  return isinf(len) || isnan(len) ? diagonal : min(len, diagonal);
}

void main() {
  if (kMode == LB_MODE_ERROR) {
    // Vertical distance between the tessellated surface and the true heightfield, in pixels.
    vec3 truePoint = vec3(inWorld.x, terrainHeight(inWorld.xz), inWorld.z);
    outColor = vec4(screenError(inWorld, truePoint), 0.0, 0.0, 1.0);
    return;
  }
  vec3 n = kHeightNormals ? terrainNormal(inWorld.xz) : mapNormal(inWorld);
  float diffuse = max(dot(n, normalize(frame.light.xyz)), 0.0);
  float shade = 0.25 + 0.75 * diffuse;
  vec3 base;
  if (kMode == LB_MODE_SHADED) {
    float slope = 1.0 - n.y;
    base = mix(vec3(0.36, 0.45, 0.25), vec3(0.45, 0.40, 0.35), smoothstep(0.15, 0.35, slope));
  } else {
    base = heat(inLevel);
  }
  vec3 c = kMode == LB_MODE_WIREFRAME ? base : base * shade;
  // The clear colour is pure magenta; keep every terrain pixel visibly off it (crack detection).
  outColor = vec4(c.r, max(c.g, 0.02), c.b, 1.0);
}
