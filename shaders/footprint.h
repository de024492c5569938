// Which mip level of the normal map shades a point: the one function the raster (terrain.frag),
// the GPU ray cast (raycast.glsl) and the CPU ray cast (metrics/raycast_shade.cpp) all call, so an
// image and its ray-cast truth filter their normals alike and differ in geometry only. C++ and
// GLSL alike; `LB_FP_DIV` and `LB_FP_SQRT` may be defined first (the GPU ray cast defines them as
// its correctly rounded division and root, so its levels equal the CPU's bit for bit).
//
// The level is log2 of the pixel's footprint over the normal map's texel, both as areas:
//   footprint^2 = (d * pixelAngle)^2 * d / rise,   level = log2(footprint^2 / texelArea) / 2,
// d the distance from the eye, rise the height difference |y - eyeY| (d / rise = 1 / sin of the
// view ray's elevation: a ground pixel stretches along the view by that much), at most 8 times
// (kShadingMaxStretch^2 = 64 in area terms: rise >= d / 64 caps the stretch; beyond it the normal
// map is blurred across the view as much as along it). log2 is taken piecewise linear between
// powers of two (x = m 2^e, m in [1, 2): e + m - 1; at most 0.086 below log2), so every step is an
// exact IEEE operation or one of the two above. The level is clamped to [0, the map's last level].
#ifndef LB_FOOTPRINT_H
#define LB_FOOTPRINT_H

#ifndef LB_FP_DIV
#define LB_FP_DIV(a, b) ((a) / (b))
#endif
#ifndef LB_FP_SQRT
#define LB_FP_SQRT(a) sqrt(a)
#endif

#ifdef __cplusplus
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
namespace lb {
#define LB_FP_PRECISE
#define LB_FP_INLINE inline
using glm::vec3;
using std::abs;
using std::sqrt;
#else
#define LB_FP_PRECISE precise
#define LB_FP_INLINE
#endif

#define LB_SHADING_MIN_RISE (1.0 / 64.0)

// The mip levels of a normal map of w x h texels down to 1 x 1 (Vulkan's full chain).
LB_FP_INLINE int normalMapLevels(int w, int h) {
  int n = 1;
  for (int s = w > h ? w : h; s > 1; s >>= 1) ++n;
  return n;
}

// e + m - 1 for x = m 2^e, m in [1, 2): exact.
LB_FP_INLINE float piecewiseLog2(float x) {
  int e;
#ifdef __cplusplus
  const float m = std::frexp(x, &e);  // [0.5, 1)
#else
  const float m = frexp(x, e);
#endif
  LB_FP_PRECISE float r = float(e - 1) + (2.0f * m - 1.0f);
  return r;
}

// world: the shaded point; eye: the camera; pixelAngle: one pixel's angle at the image centre
// (shadingPixelAngle); extent and samples: the terrain's (texel = extent / (samples - 1)).
LB_FP_INLINE float shadingLevel(vec3 world, vec3 eye, float pixelAngle, float extent, int samplesX, int samplesZ) {
  LB_FP_PRECISE vec3 v = world - eye;
  LB_FP_PRECISE float d2 = v.x * v.x + v.y * v.y + v.z * v.z;
  const float d = LB_FP_SQRT(d2);
  LB_FP_PRECISE float minRise = d * float(LB_SHADING_MIN_RISE);
  const float rise = abs(v.y) > minRise ? abs(v.y) : minRise;
  const float tx = LB_FP_DIV(extent, float(samplesX > 1 ? samplesX - 1 : 1));
  const float tz = LB_FP_DIV(extent, float(samplesZ > 1 ? samplesZ - 1 : 1));
  LB_FP_PRECISE float num = d2 * d * (pixelAngle * pixelAngle);
  LB_FP_PRECISE float den = rise * (tx * tz);
  const float r2 = LB_FP_DIV(num, den);
  if (!(r2 > 1.0f)) return 0.0f;  // finer than a texel (and NaN at the eye itself)
  LB_FP_PRECISE float level = 0.5f * piecewiseLog2(r2 < 1e30f ? r2 : 1e30f);
  const float last = float(normalMapLevels(samplesX, samplesZ) - 1);
  return level < last ? level : last;
}

#ifdef __cplusplus
// One pixel's angle at the image centre of a projection (camera/camera_matrices.h) on an image
// heightPx pixels high: 2 tan(fov / 2) / heightPx, in float.
inline float shadingPixelAngle(const glm::mat4& proj, int heightPx) {
  return 2.0f / (std::fabs(proj[1][1]) * float(heightPx));
}
}  // namespace lb
#endif
#endif
